#include "validation/runner/registry/scenario_option_tables.h"

#include <numbers>
#include <string>

#include "datasets/range_bearing_simulator.h"
#include "datasets/simulation_limits.h"
#include "src/core/parameter_table.h"

namespace phdslam::validation {
namespace {

using params::Between;
using params::EnumField;
using params::Field;
using params::IntField;
using params::NumberField;

using datasets::kMaxDistance;
constexpr double kPi = std::numbers::pi;

// The nine sub-datasets of the MRCLAM collection.
constexpr int kMrclamDatasets = 9;
// m, the largest wheelbase of a simulated vehicle.
constexpr double kMaxWheelbase = 100.0;
// The smallest speed (m/s) and wheelbase (m) of the simulators that steer a car-like vehicle:
// the steering angle divides by them, and far below any vehicle's values the controls become NaN.
constexpr double kMinVehicleSpeed = 0.01;
constexpr double kMinWheelbase = 0.01;

// (0, max]
params::Bounds PositiveUpTo(double max) { return {0.0, max, true, false}; }

nlohmann::json MatrixJson(const Mat2& m) {
  return nlohmann::json::array(
      {nlohmann::json::array({m(0, 0), m(0, 1)}), nlohmann::json::array({m(1, 0), m(1, 1)})});
}

// A 2 x 2 covariance, written as [[a, b], [c, d]] and read from that form or from the two
// diagonal entries [a, d]. Symmetry and definiteness are checked by the options' Validate().
Mat2 ReadMatrix(const nlohmann::json& v, const std::string& key) {
  const std::string form =
      "expected [[a, b], [c, d]] or the diagonal [a, d], got " + params::Shown(v);
  if (!v.is_array() || v.size() != 2) params::Fail(key, form);
  Mat2 m = Mat2::Zero();
  if (v[0].is_number() && v[1].is_number()) {
    for (int i = 0; i < 2; ++i) {
      m(i, i) = params::ReadNumber(v[i], key, Between(0.0, datasets::kMaxVariance));
    }
    return m;
  }
  for (int i = 0; i < 2; ++i) {
    if (!v[i].is_array() || v[i].size() != 2) params::Fail(key, form);
    for (int j = 0; j < 2; ++j) {
      m(i, j) = params::ReadNumber(v[i][j], key,
                                   Between(-datasets::kMaxVariance, datasets::kMaxVariance));
    }
  }
  return m;
}

template <class T, class Access>
Field<T> CovarianceField(std::string key, Access access) {
  return {key, "a 2x2 covariance [[a, b], [c, d]] or its diagonal [a, d], entries within +-1e6",
          [access](const T& p) { return MatrixJson(access(p)); },
          [access, key](const nlohmann::json& v, T& p) { access(p) = ReadMatrix(v, key); }};
}

// A pose [x, y, theta] (m, m, rad).
template <class T, class Access>
Field<T> PoseField(std::string key, Access access) {
  return {key, "an array [x, y, theta] (m, m, rad), |x|, |y| <= 1e7 m, |theta| <= 2 pi",
          [access](const T& p) {
            return nlohmann::json::array({access(p)(0), access(p)(1), access(p)(2)});
          },
          [access, key](const nlohmann::json& v, T& p) {
            if (!v.is_array() || v.size() != 3) {
              params::Fail(key, "expected an array [x, y, theta], got " + params::Shown(v));
            }
            for (int i = 0; i < 2; ++i) {
              access(p)(i) = params::ReadNumber(
                  v[i], key, Between(-datasets::kMaxCoordinate, datasets::kMaxCoordinate));
            }
            access(p)(2) = params::ReadNumber(v[2], key, Between(-2.0 * kPi, 2.0 * kPi));
          }};
}

// The field of view and its buffers, common to every range-bearing scenario.
template <class T>
std::vector<Field<T>> SensorRows() {
  return {
      NumberField<T>(
          "fov_range", [](auto& o) -> auto& { return o.fov_range; }, PositiveUpTo(kMaxDistance)),
      NumberField<T>(
          "fov_half_angle", [](auto& o) -> auto& { return o.fov_half_angle; }, PositiveUpTo(kPi)),
      NumberField<T>(
          "range_buffer", [](auto& o) -> auto& { return o.range_buffer; },
          Between(0.0, kMaxDistance)),
      NumberField<T>(
          "angle_buffer", [](auto& o) -> auto& { return o.angle_buffer; }, Between(0.0, kPi)),
      CovarianceField<T>(
          "measurement_noise_cov", [](auto& o) -> auto& { return o.measurement_noise_cov; }),
      CovarianceField<T>(
          "control_noise_cov", [](auto& o) -> auto& { return o.control_noise_cov; }),
  };
}

// Constant pD and Poisson clutter of the synthetic scenarios.
template <class T>
std::vector<Field<T>> DetectionRows() {
  return {
      NumberField<T>("detection_probability",
                     [](auto& o) -> auto& { return o.detection_probability; },
                     {0.0, 1.0, true, false}),
      NumberField<T>(
          "clutter_rate", [](auto& o) -> auto& { return o.clutter_rate; },
          Between(0.0, datasets::kMaxClutterRate)),
  };
}

}  // namespace

const params::ParameterTable<datasets::SyntheticOptions>& PaperSyntheticOptionsTable() {
  using O = datasets::SyntheticOptions;
  static const params::ParameterTable<O> table(
      params::Rows<O>({DetectionRows<O>(), SensorRows<O>()}));
  return table;
}

const params::ParameterTable<datasets::VictoriaParkOptions>& VictoriaParkOptionsTable() {
  using O = datasets::VictoriaParkOptions;
  static const params::ParameterTable<O> table(params::Rows<O>({
      {
          NumberField<O>("detection_probability_max",
                         [](auto& o) -> auto& { return o.detection_probability_max; },
                         {0.0, 1.0, true, false}),
          NumberField<O>("detection_probability_nominal",
                         [](auto& o) -> auto& { return o.detection_probability_nominal; },
                         {0.0, 1.0, true, true}),
          NumberField<O>(
              "clutter_rate", [](auto& o) -> auto& { return o.clutter_rate; },
              Between(0.0, datasets::kMaxClutterRate)),
      },
      SensorRows<O>(),
  }));
  return table;
}

const params::ParameterTable<datasets::GeneratorOptions>& GeneratedOptionsTable() {
  using O = datasets::GeneratorOptions;
  static const params::ParameterTable<O> table(params::Rows<O>({
      {
          NumberField<O>(
              "dt", [](auto& o) -> auto& { return o.dt; }, PositiveUpTo(datasets::kMaxTimeStep)),
          NumberField<O>(
              "speed", [](auto& o) -> auto& { return o.speed; }, Between(0.0, datasets::kMaxSpeed)),
          NumberField<O>(
              "turn_amplitude", [](auto& o) -> auto& { return o.turn_amplitude; },
              Between(0.0, datasets::kMaxTurnRate)),
          IntField<O>(
              "landmarks", [](auto& o) -> auto& { return o.landmarks; },
              Between(0, datasets::kMaxSimulatedLandmarks)),
          NumberField<O>(
              "corridor_half_width", [](auto& o) -> auto& { return o.corridor_half_width; },
              Between(datasets::kMinCorridorHalfWidth, kMaxDistance)),
      },
      DetectionRows<O>(),
      SensorRows<O>(),
      {PoseField<O>(
          "initial_pose", [](auto& o) -> auto& { return o.initial_pose; })},
  }));
  return table;
}

const params::ParameterTable<datasets::ScPhdSimOptions>& ScPhdSimOptionsTable() {
  using O = datasets::ScPhdSimOptions;
  static const params::ParameterTable<O> table(params::Rows<O>({
      {
          NumberField<O>(
              "dt", [](auto& o) -> auto& { return o.dt; }, PositiveUpTo(datasets::kMaxTimeStep)),
          NumberField<O>(
              "speed", [](auto& o) -> auto& { return o.speed; },
              Between(kMinVehicleSpeed, datasets::kMaxSpeed)),
          NumberField<O>(
              "circle_radius", [](auto& o) -> auto& { return o.circle_radius; },
              PositiveUpTo(kMaxDistance)),
          NumberField<O>(
              "wheelbase", [](auto& o) -> auto& { return o.wheelbase; },
              Between(kMinWheelbase, kMaxWheelbase)),
          IntField<O>(
              "landmarks", [](auto& o) -> auto& { return o.landmarks; },
              Between(0, datasets::kMaxSimulatedLandmarks)),
          NumberField<O>(
              "map_inner_radius", [](auto& o) -> auto& { return o.map_inner_radius; },
              Between(0.0, kMaxDistance)),
          NumberField<O>(
              "map_outer_radius", [](auto& o) -> auto& { return o.map_outer_radius; },
              PositiveUpTo(kMaxDistance)),
      },
      DetectionRows<O>(),
      SensorRows<O>(),
  }));
  return table;
}

const params::ParameterTable<datasets::MrclamOptions>& MrclamOptionsTable() {
  using O = datasets::MrclamOptions;
  static const params::ParameterTable<O> table(params::Rows<O>({
      {
          IntField<O>(
              "dataset", [](auto& o) -> auto& { return o.dataset; }, Between(1, kMrclamDatasets)),
          IntField<O>(
              "robot", [](auto& o) -> auto& { return o.robot; },
              Between(1, datasets::kMrclamRobots)),
          params::BoolField<O>(
              "drop_non_landmarks", [](auto& o) -> auto& { return o.drop_non_landmarks; }),
      },
      DetectionRows<O>(),
      SensorRows<O>(),
  }));
  return table;
}

const params::ParameterTable<datasets::GlmbSimOptions>& GlmbSimOptionsTable() {
  using O = datasets::GlmbSimOptions;
  using P = datasets::GlmbDataProtocol;
  static const params::ParameterTable<O> table(params::Rows<O>({
      {
          NumberField<O>(
              "dt", [](auto& o) -> auto& { return o.dt; }, PositiveUpTo(datasets::kMaxTimeStep)),
          NumberField<O>(
              "speed", [](auto& o) -> auto& { return o.speed; },
              Between(kMinVehicleSpeed, datasets::kMaxSpeed)),
          NumberField<O>(
              "wheelbase", [](auto& o) -> auto& { return o.wheelbase; },
              Between(kMinWheelbase, kMaxWheelbase)),
          IntField<O>(
              "landmarks", [](auto& o) -> auto& { return o.landmarks; },
              Between(0, datasets::kMaxSimulatedLandmarks)),
          NumberField<O>(
              "landmark_offset", [](auto& o) -> auto& { return o.landmark_offset; },
              Between(0.0, kMaxDistance)),
          EnumField<O, P>(
              "data_protocol", [](auto& o) -> auto& { return o.data_protocol; },
              {{P::kPerSeed, "per-seed"}, {P::kSingleRealisation, "single-realisation"}}),
          IntField<O>(
              "data_seed", [](auto& o) -> auto& { return o.data_seed; }, Between(0, 1e9)),
      },
      DetectionRows<O>(),
      SensorRows<O>(),
  }));
  return table;
}

}  // namespace phdslam::validation
