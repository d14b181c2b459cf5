// The dense grid of light and view directions the GPU-against-CPU agreement tests share: every
// incidence and exit angle up to 89.9° (denser towards grazing), relative azimuths 0…180°, the
// exact mirror direction and its close neighbourhood, l = v, and (optionally) directions a hair
// above the horizon; and the comparison of a GPU material with its CPU model on it.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "brdf/brdf.h"
#include "render/gpu_material.h"
#include "render/material_probe.h"

namespace brdfrig::render::testing {

inline Eigen::Vector3d Direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

struct DirectionGrid {
  std::vector<Eigen::Vector3f> light, view;  // in the frame where the normal is +z
  void Add(const Eigen::Vector3d& l, const Eigen::Vector3d& v) {
    light.push_back(l.cast<float>());
    view.push_back(v.cast<float>());
  }
};

inline DirectionGrid MakeGrid(bool horizon) {
  constexpr double kDeg = M_PI / 180;
  DirectionGrid grid;
  const int n_theta = 48, n_phi = 25;
  std::vector<double> thetas;
  for (int i = 0; i < n_theta; ++i) {
    const double u = static_cast<double>(i) / (n_theta - 1);
    thetas.push_back((1 - (1 - u) * (1 - u)) * 89.9 * kDeg);
  }
  for (double ti : thetas) {
    const Eigen::Vector3d l = Direction(ti, 0.3);
    for (double to : thetas) {
      for (int k = 0; k < n_phi; ++k) grid.Add(l, Direction(to, 0.3 + M_PI * k / (n_phi - 1)));
    }
    // The exact mirror direction (h = n bit for bit), its neighbourhood, and l = v.
    const Eigen::Vector3d mirror(-l.x(), -l.y(), l.z());
    grid.Add(l, mirror);
    grid.Add(l, l);
    for (double d : {1e-5, 1e-4, 1e-3, 3e-3, 0.01, 0.03, 0.1}) {
      const double to = std::min(ti + d, 89.9 * kDeg);
      grid.Add(l, Direction(to, 0.3 + M_PI));
      grid.Add(l, Direction(ti, 0.3 + M_PI + d));
    }
  }
  // A hair above the horizon (cos 1e-6 and 1e-20): finite, as on the CPU.
  for (double z : {1e-6, 1e-20}) {
    if (!horizon) break;
    const Eigen::Vector3d l = Eigen::Vector3d(1, 0, z).normalized();
    for (double to : thetas) {
      grid.Add(l, Direction(to, M_PI));
      grid.Add(Direction(to, 0.5), l);
    }
  }
  return grid;
}

struct Agreement {
  double max_relative = 0;
  Eigen::Vector3d light_at = Eigen::Vector3d::Zero(), view_at = Eigen::Vector3d::Zero();
  int checked = 0;
};

// Max over the grid (rotated so that the normal is `normal`) of |gpu − cpu| / max(|cpu|,
// floor(l, v)), over the pairs `use` accepts (all when empty), l and v in the grid's frame. The
// CPU evaluates at exactly the float vectors the GPU saw.
inline Agreement CompareOnGrid(
    const GpuMaterial& material, const brdf::Brdf& cpu_model, const DirectionGrid& grid,
    const Eigen::Vector3d& normal,
    const std::function<double(const Eigen::Vector3d&, const Eigen::Vector3d&)>& floor,
    const std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)>& use = {}) {
  const Eigen::Quaterniond rotation =
      Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), normal);
  const Eigen::Vector3f n = normal.cast<float>();
  const int width = 512;
  const int count = static_cast<int>(grid.light.size());
  const int height = (count + width - 1) / width;
  cv::Mat light(height, width, CV_32FC3, cv::Scalar(0, 0, 1)),
      view(height, width, CV_32FC3, cv::Scalar(0, 0, 1));
  std::vector<Eigen::Vector3f> l_used(count), v_used(count);
  for (int i = 0; i < count; ++i) {
    l_used[i] = (rotation * grid.light[i].cast<double>()).cast<float>();
    v_used[i] = (rotation * grid.view[i].cast<double>()).cast<float>();
    light.at<cv::Vec3f>(i / width, i % width) = {l_used[i].x(), l_used[i].y(), l_used[i].z()};
    view.at<cv::Vec3f>(i / width, i % width) = {v_used[i].x(), v_used[i].y(), v_used[i].z()};
  }
  const cv::Mat gpu = EvalMaterialOnGpu(material, light, view, n);
  Agreement worst;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d l = grid.light[i].cast<double>(), v = grid.view[i].cast<double>();
    if (use && !use(l, v)) continue;
    const brdf::Rgb cpu =
        cpu_model.Eval(l_used[i].cast<double>(), v_used[i].cast<double>(), n.cast<double>());
    const cv::Vec3f g = gpu.at<cv::Vec3f>(i / width, i % width);
    const double lowest = floor(l, v);
    for (int c = 0; c < 3; ++c) {
      const double rel = std::abs(g[c] - cpu[c]) / std::max(std::abs(cpu[c]), lowest);
      if (!(rel <= worst.max_relative)) {
        worst.max_relative = rel;
        worst.light_at = l;
        worst.view_at = v;
      }
      ++worst.checked;
    }
  }
  return worst;
}

}  // namespace brdfrig::render::testing
