#include "pathtrace/light_sampler.h"

#include "patch/patch_set.h"
#include "pathtrace/surface_geometry.h"

namespace radwalk {

LightSampler::LightSampler(const PatchSet& patches, const SurfaceGeometry& geometry, LightSelection selection)
    : patches_(&patches), geometry_(&geometry), slot_(patches.size(), -1) {
  std::vector<double> weights;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (!(patches.E[i] > 0).any() || !(patches.area[i] > 0)) continue;
    slot_[i] = static_cast<int>(emitters_.size());
    emitters_.push_back(static_cast<PatchIndex>(i));
    power_ += patches.area[i] * patches.E[i];
    weights.push_back(selection == LightSelection::power ? patches.area[i] * patches.E[i].mean()
                                                         : patches.area[i]);
  }
  if (emitters_.empty()) return;
  choice_ = AliasTable(weights);
  for (std::size_t k = 0; k < emitters_.size(); ++k) {
    const auto j = static_cast<std::size_t>(emitters_[k]);
    pdf_area_.push_back(choice_.pdf(k) / patches.area[j]);
    Le_.push_back(patches.E[j] * kInvPi);
  }
}

LightSample LightSampler::sample(double u_select, double u1, double u2) const {
  const std::size_t k = choice_.sample(u_select);
  const PatchIndex j = emitters_[k];
  LightSample s;
  s.patch = j;
  s.point = geometry_->sample_point(j, u1, u2);
  s.normal = geometry_->normal(j, s.point);
  s.Le = Le_[k];
  s.pdf_area = pdf_area_[k];
  return s;
}

double LightSampler::pmf(PatchIndex i) const {
  const int k = slot_[static_cast<std::size_t>(i)];
  return k < 0 ? 0.0 : choice_.pdf(static_cast<std::size_t>(k));
}

double LightSampler::pdf_area(PatchIndex i) const {
  const int k = slot_[static_cast<std::size_t>(i)];
  return k < 0 ? 0.0 : pdf_area_[static_cast<std::size_t>(k)];
}

}  // namespace radwalk
