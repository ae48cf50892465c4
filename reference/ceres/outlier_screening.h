// Screening of a given association for gross outliers (README.md, "Outliers in the known
// association"). A labelled measurement whose squared whitened range-bearing residual at a solved
// trajectory and map exceeds a chi-square threshold cannot come from its label (on UTIAS MRCLAM a
// misread barcode gives a bearing off by about pi, chi-square ~5e4): it is left out of the
// association, so that a squared-loss solve is not pulled by it.
#pragma once

#include <vector>

#include "datasets/scenario.h"
#include "reference/ceres/landmark_association.h"
#include "src/core/types.h"

namespace phdslam::reference {

/// Squared whitened residual e^T R^-1 e of measurement z at pose x and landmark m (bearing
/// difference wrapped); infinity when m coincides with x.
double MeasurementChi2(const Pose& x, const Landmark& m, const Measurement& z,
                       const Mat2& measurement_cov);

/// Sets to kUnassociated every associated measurement whose MeasurementChi2 at (poses, landmarks)
/// exceeds `chi2`, except a landmark's last remaining measurement (every landmark of the
/// association keeps at least one). Returns the number of measurements dropped. Throws
/// std::invalid_argument when chi2 is not positive or the association does not fit the scenario.
int DropOutlierMeasurements(const datasets::Scenario& scenario, const std::vector<Pose>& poses,
                            const std::vector<Landmark>& landmarks, double chi2,
                            Association* association);

}  // namespace phdslam::reference
