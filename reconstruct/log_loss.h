// The loss every rung is fitted and judged with (ACCURACY.md): per sample and channel
//
//     r = ln(eps_c + f_model · cos_i) − ln(eps_c + f_data · cos_i),   weight cos_i · cos_o · pixels
//
// eps_c is a fraction (1 %) of the data's 10th percentile of f·cos_i in that channel (weighted
// by LossWeight, so it is a percentile of the measure, not of the sample count): small
// enough that a dark channel's level is fitted in relative terms (ln(1 + f) would be an
// absolute error there and never fit it), large enough that noise about zero does not make
// ln explode. The weight is the cosine-weighted measure of the (l, v) pair, so a sample counts
// as much as it contributes to rendered radiance.
#pragma once

#include <array>
#include <vector>

#include "brdf/brdf.h"
#include "reconstruct/direction_samples.h"

namespace brdfrig::reconstruct {

using Epsilon = std::array<double, 3>;

// The q-quantile (q in [0, 1]) of `values` where each counts with its weight (> 0; others are
// ignored). A sample's count says little: the direction samples are pixel blocks, split finely
// where the BRDF changes fast (the highlight) and coarsely where it is flat, so most samples
// sit on the highlight while most of the cut-out's pixels do not. NaN when nothing has weight.
double WeightedQuantile(std::vector<std::pair<double, double>> value_weight, double q);

// eps_c from the data (never 0: a channel whose 10th percentile is <= 0 gets 1e-6 of its
// largest value, or 1e-12).
Epsilon LossEpsilon(const std::vector<DirectionSample>& samples, double fraction = 0.01);

// Weighted RMS of r over samples and channels (the validation score); NaN without samples or
// bounds.
// `bounds`: blocks darker than the photo's noise floor (DirectionSamples::bounds), each saying
// the material is no brighter than its f there. A bound adds r where the model lies above it
// and 0 where it does not, with the same weight as a sample: the photo contradicts a model that
// is bright where it saw nothing, and agrees with any model that is dark there.
double LogLossRms(const brdf::Brdf& model, const std::vector<DirectionSample>& samples,
                  const Epsilon& eps, const std::vector<DirectionSample>& bounds = {});

// The weight of one sample (cos_i · cos_o · pixels).
inline double LossWeight(const DirectionSample& s) { return s.l.z() * s.v.z() * s.weight; }

}  // namespace brdfrig::reconstruct
