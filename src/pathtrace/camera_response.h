#pragma once
// The response of a camera view as a measurement over patches (solve/measurement.h, docs/theory/adjoint.md).
//
// A pixel's value is the mean radiance over its film square (camera.h). In the discrete model a primary ray that
// hits the front of patch i sees radiance B_i / pi (Lambertian; one-sided: a back or a miss sees 0), so the mean
// pixel value of the image is
//   Lbar = (1 / P) sum_pixels (1 / A_film_px) int_pixel B_{i(x)} / pi dx = sum_i f_i B_i / pi,
// f_i the fraction of the film whose primary rays land on the front of patch i. With
//   R_i = f_i / (pi A_i)
// the measurement M = <R, B>_A = sum_i A_i R_i B_i equals Lbar: M is the image's mean pixel radiance (W/m^2/sr
// in the scene's units). f_i is computed by n x n film points per pixel, the centres of the pixel's n x n
// sub-squares (deterministic: no random numbers). A pixel whose points all land on one patch (or all miss) is
// exact; a pixel split by an edge has a fraction error of at most 1 per pixel and typically 1 / n.
#include <Eigen/Core>

#include "pathtrace/camera.h"
#include "patch/patch_set.h"
#include "visibility/visibility.h"

namespace radwalk {

struct CameraResponse {
  Eigen::VectorXd R;              // R_i = f_i / (pi A_i)
  Eigen::VectorXd fraction;       // f_i
  long boundary_pixels = 0;       // pixels whose points did not all see the same patch (or all miss)
  long pixels = 0;                // width x height
};

// Throws InputError if points_per_side < 1. Parallel over rows; the result does not depend on the thread count
// (each pixel's count is its own, summed in pixel order per row and rows in order).
CameraResponse camera_response(const PinholeCamera& camera, const Visibility& visibility, const PatchSet& patches,
                               int points_per_side = 4);

}  // namespace radwalk
