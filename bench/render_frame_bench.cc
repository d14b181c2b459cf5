// Frame time of the 50K-triangle test object at 1280×720 with each material shader, in one run,
// as a ratio to Lambert (the floor of any shading): the seed's slices, the reference GGX, the
// model ladder's microfacet rungs (ggx, beckmann, the data-driven table: issue 14 asks the
// default rung for <= 1.5x Lambert), the prior rung's Rusinkiewicz table (of the measured
// "steel" on the default 64 x 32 x 8 grid; the same target) and a MERL table.
// Run: build/release/bench/bench_render_frame [frames per round] [rounds] [name filter]
// (with a filter, only Lambert and the shaders whose name contains it)
// On a shared machine use short rounds and many of them: the best round of each shader is the
// one least disturbed by other work.
#include <Eigen/Geometry>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "brdf/analytic.h"
#include "brdf/merl.h"
#include "brdf/microfacet_model.h"
#include "brdf/microfacet_terms.h"
#include "brdf/nbrdf_library.h"
#include "brdf/rusinkiewicz_table.h"
#include "brdf/slice_model.h"
#include "common/angles.h"
#include "geometry/camera.h"
#include "render/gl_context.h"
#include "render/renderer.h"

using namespace brdfrig;

namespace {

brdf::SliceModel SixSlices() {
  std::vector<brdf::Slice> slices;
  for (int k = 0; k < 6; ++k) {
    brdf::Slice s;
    s.theta_in = Radians(15 + 10 * k);
    for (auto& c : s.channel) c = {20.0 + 5 * k, 0.1, 0.03, 0.06};
    slices.push_back(s);
  }
  return brdf::SliceModel(slices);
}

// A ladder rung with the reference GGX's colours; `table` adds a 32-knot ln D table sampled
// from GGX(alpha) up to 40° with a tail, and five Fresnel knots (the most work per pixel).
brdf::MicrofacetModel Rung(brdf::Distribution distribution, bool fresnel_knots) {
  brdf::MicrofacetModelParams p;
  p.distribution = distribution;
  p.diffuse = brdf::Rgb(0.1, 0.05, 0.03);
  p.f0 = brdf::Rgb(0.9, 0.6, 0.35);
  p.alpha = 0.1;
  if (fresnel_knots) p.fresnel_knots = {0, -0.05, 0.1, -0.2, 0.3};
  if (distribution == brdf::Distribution::kTable) {
    const int knots = 32;
    p.max_theta_h = Radians(40);
    p.shadowing_alpha = 0.1;
    for (int k = 0; k < knots; ++k) {
      const double theta = brdf::microfacet::TableKnotThetaH(k, knots, p.max_theta_h);
      p.log_d.push_back(brdf::microfacet::LogGgxD(std::cos(theta), 0.1));
    }
  }
  return brdf::MicrofacetModel(p);
}

render::View MakeView() {
  render::View view;
  view.intrinsics = {1280, 720, 1100, 1100, 640, 360};
  view.pose = geometry::LookAt({0.0, -0.17, 0.12}, {0, 0, 0}, {0, 0, 1});
  return view;
}

double MillisecondsPerFrame(render::Renderer& renderer, const render::View& view,
                            const render::GpuMesh& mesh, const render::GpuMaterial& material,
                            int frames) {
  const std::vector<render::PointLight> lights = {{{0.1, 0.1, 0.3}, brdf::Rgb::Ones()}};
  renderer.Draw(view, lights, {{&mesh, &material}});  // warm-up: shader compile, first use
  renderer.Finish();
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) renderer.Draw(view, lights, {{&mesh, &material}});
  renderer.Finish();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
             .count() /
         frames;
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::stoi(argv[1]) : 20;
  const int rounds = argc > 2 ? std::stoi(argv[2]) : 3;
  auto context = render::CreateHeadlessContext();
  std::printf("GL: %s\n", context->Description().c_str());
  const render::Mesh mesh = render::MakeTestObject(50000);
  const render::GpuMesh gpu_mesh(mesh);
  render::Renderer renderer(1280, 720);
  const render::View view = MakeView();

  const brdf::MicrofacetParams ggx{brdf::Rgb(0.1, 0.05, 0.03), brdf::Rgb(0.9, 0.6, 0.35), 0.1};
  struct Entry {
    std::string name;
    std::unique_ptr<render::GpuMaterial> material;
  };
  std::vector<Entry> entries;
  entries.push_back({"lambert", render::GpuMaterial::Lambert(brdf::Rgb::Constant(0.5))});
  entries.push_back({"ggx (reference)", render::GpuMaterial::Ggx(ggx)});
  entries.push_back(
      {"rung ggx", render::GpuMaterial::Microfacet(Rung(brdf::Distribution::kGgx, false))});
  entries.push_back({"rung beckmann",
                     render::GpuMaterial::Microfacet(Rung(brdf::Distribution::kBeckmann, false))});
  entries.push_back({"rung microfacet (32-knot table)",
                     render::GpuMaterial::Microfacet(Rung(brdf::Distribution::kTable, false))});
  entries.push_back({"rung microfacet (table + 5 Fresnel knots)",
                     render::GpuMaterial::Microfacet(Rung(brdf::Distribution::kTable, true))});
  entries.push_back({"slice model (spline)", render::GpuMaterial::SliceModel(SixSlices())});
  auto linear = render::GpuMaterial::SliceModel(SixSlices());
  linear->SetLinearInterpolation(true);
  entries.push_back({"slice model (linear)", std::move(linear)});
  const brdf::RusinkiewiczGrid grid;
  const brdf::RusinkiewiczTable prior(grid,
                                      brdf::TabulateBrdf(brdf::ReadNbrdfMaterial("steel"), grid));
  entries.push_back({"prior table (steel, 64x32x8)", render::GpuMaterial::Table(prior)});
  entries.push_back(
      {"merl table", render::GpuMaterial::Merl(brdf::MerlTable::Tabulate(brdf::Ggx(ggx)))});

  if (argc > 3) {
    const std::string filter = argv[3];
    std::erase_if(entries, [&](const Entry& e) {
      return e.name != "lambert" && e.name.find(filter) == std::string::npos;
    });
  }

  // Interleave rounds so machine noise hits every shader alike; keep each shader's best round.
  std::vector<double> best(entries.size(), 1e300);
  for (int round = 0; round < rounds; ++round) {
    for (std::size_t i = 0; i < entries.size(); ++i) {
      best[i] = std::min(
          best[i], MillisecondsPerFrame(renderer, view, gpu_mesh, *entries[i].material, frames));
    }
  }
  std::printf("%zu triangles, 1280x720, %d frames x %d rounds (best round)\n\n",
              mesh.TriangleCount(), frames, rounds);
  std::printf("| shader | ms/frame | frames/s | x Lambert |\n|---|---:|---:|---:|\n");
  for (std::size_t i = 0; i < entries.size(); ++i) {
    std::printf("| %s | %.2f | %.1f | %.2f |\n", entries[i].name.c_str(), best[i], 1000.0 / best[i],
                best[i] / best[0]);
  }
  return 0;
}
