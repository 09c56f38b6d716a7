#pragma once
// LightSampler: next-event estimation's choice of a point on the emitters (patches with E > 0 in some channel).
//
// An emitter j is chosen with probability P_j proportional to its power A_j * mean(E_j) (LightSelection::power)
// or to its area A_j (LightSelection::area), by an alias table (O(1) per sample whatever the number of emitters),
// then a point y uniformly on its surface (SurfaceGeometry::sample_point),
// so the area density of y is
//   pdf_area(y) = P_j / A_j        (1/m^2 in the mesh's length unit),
// and the emitter's front normal at y (SurfaceGeometry::normal).
// Converted to solid angle at a receiver x: pdf_w = pdf_area * |x - y|^2 / cos(theta_y). Emission is Lambertian
// on the front side: Le = E_j / pi (W / (m^2 sr)).
#include <cstddef>
#include <vector>

#include "core/discrete_distribution.h"
#include "core/types.h"

namespace radwalk {

struct PatchSet;
class SurfaceGeometry;

enum class LightSelection { power, area };

struct LightSample {
  PatchIndex patch = -1;
  Vec3 point;
  Vec3 normal;     // front normal of the emitter at point
  Rgb Le;          // emitted radiance toward the front
  double pdf_area = 0;
};

class LightSampler {
 public:
  // Keeps references to patches and geometry (they must outlive it).
  LightSampler(const PatchSet& patches, const SurfaceGeometry& geometry,
               LightSelection selection = LightSelection::power);
  bool empty() const { return emitters_.empty(); }
  const std::vector<PatchIndex>& emitters() const { return emitters_; }
  // u_select chooses the emitter, (u1, u2) the point on it.
  LightSample sample(double u_select, double u1, double u2) const;
  // Probability of choosing patch i (0 for a non-emitter) and the area density of points on it.
  double pmf(PatchIndex i) const;
  double pdf_area(PatchIndex i) const;
  // Total emitted power per channel, sum_j A_j E_j (W).
  const Rgb& total_power() const { return power_; }

 private:
  const PatchSet* patches_;
  const SurfaceGeometry* geometry_;
  std::vector<PatchIndex> emitters_;
  std::vector<int> slot_;  // patch -> index in emitters_, -1 for non-emitters
  AliasTable choice_;               // over emitters_
  std::vector<double> pdf_area_;    // P_j / A_j of each emitter
  std::vector<Rgb> Le_;             // E_j / pi of each emitter
  Rgb power_ = Rgb::Zero();
};

}  // namespace radwalk
