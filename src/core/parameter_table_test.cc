#include "src/core/parameter_table.h"

#include <gtest/gtest.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace phdslam::params {
namespace {

enum class Mode { kFast, kExact };

struct Inner {
  double gate = 9.0;
  bool strict = false;
};

struct Settings {
  int count = 3;
  double rate = 0.5;
  Mode mode = Mode::kFast;
  Eigen::Matrix3d noise = Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal();
  double threshold = 1.0;
  Inner inner;
};

const ParameterTable<Inner>& InnerTable() {
  static const ParameterTable<Inner> table({
      NumberField<Inner>(
          "gate", [](auto& p) -> auto& { return p.gate; }, Above(0.0)),
      BoolField<Inner>(
          "strict", [](auto& p) -> auto& { return p.strict; }),
  });
  return table;
}

const ParameterTable<Settings>& Table() {
  using S = Settings;
  static const ParameterTable<S> table(Rows<S>({
      {IntField<S>(
           "count", [](auto& p) -> auto& { return p.count; }, AtLeast(1)),
       NumberField<S>(
           "rate", [](auto& p) -> auto& { return p.rate; }, Probability()),
       EnumField<S, Mode>("mode", [](auto& p) -> auto& { return p.mode; },
                          {{Mode::kFast, "fast"}, {Mode::kExact, "exact"}}),
       DiagonalField<S, 3>(
           "noise", [](auto& p) -> auto& { return p.noise; }, AtLeast(0.0)),
       NumberOrAutomaticField<S>(
           "threshold", [](auto& p) -> auto& { return p.threshold; }, "auto")},
      Embed<S>(
          InnerTable(), [](auto& p) -> auto& { return p.inner; }),
  }));
  return table;
}

std::string ErrorOf(const nlohmann::json& overrides) {
  Settings s;
  try {
    Table().Apply(overrides, s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ParameterTable, WritesEveryRowByKey) {
  const nlohmann::json j = Table().ToJson(Settings{});
  EXPECT_EQ(j, nlohmann::json::parse(R"({"count": 3, "rate": 0.5, "mode": "fast",
      "noise": [1.0, 2.0, 3.0], "threshold": 1.0, "gate": 9.0, "strict": false})"));
}

TEST(ParameterTable, AppliesOverridesAndRoundTrips) {
  Settings s;
  Table().Apply(nlohmann::json::parse(R"({"count": 7, "rate": 1, "mode": "exact",
      "noise": [0, 0.5, 4], "threshold": "auto", "gate": 2.5, "strict": true})"),
                s);
  EXPECT_EQ(s.count, 7);
  EXPECT_EQ(s.rate, 1.0);
  EXPECT_EQ(s.mode, Mode::kExact);
  EXPECT_EQ(s.noise, Eigen::Matrix3d(Eigen::Vector3d(0.0, 0.5, 4.0).asDiagonal()));
  EXPECT_TRUE(std::isnan(s.threshold));
  EXPECT_EQ(s.inner.gate, 2.5);
  EXPECT_TRUE(s.inner.strict);
  Settings t;
  Table().Apply(Table().ToJson(s), t);
  EXPECT_EQ(Table().ToJson(t), Table().ToJson(s));
  EXPECT_EQ(Table().ToJson(s)["threshold"], "auto");
}

TEST(ParameterTable, ErrorsNameTheKeyAndTheRule) {
  EXPECT_EQ(ErrorOf({{"cuont", 1}}),
            "unknown parameter 'cuont' (known: count, rate, mode, noise, threshold, gate, "
            "strict)");
  EXPECT_EQ(ErrorOf({{"count", 0}}), "parameter 'count': must be >= 1, got 0");
  EXPECT_EQ(ErrorOf({{"count", 2.5}}), "parameter 'count': expected an integer, got 2.5");
  EXPECT_EQ(ErrorOf({{"count", "3"}}), "parameter 'count': expected an integer, got \"3\"");
  EXPECT_EQ(ErrorOf({{"rate", 1.5}}), "parameter 'rate': must be >= 0 and <= 1, got 1.5");
  EXPECT_EQ(ErrorOf({{"gate", 0}}), "parameter 'gate': must be > 0, got 0");
  EXPECT_EQ(ErrorOf({{"strict", 1}}), "parameter 'strict': expected true or false, got 1");
  EXPECT_EQ(ErrorOf({{"mode", "slow"}}),
            "parameter 'mode': expected one of \"fast\", \"exact\", got \"slow\"");
  EXPECT_EQ(ErrorOf({{"noise", {1, 2}}}),
            "parameter 'noise': expected an array of 3 numbers, got [1,2]");
  EXPECT_EQ(ErrorOf({{"noise", {1, -2, 3}}}), "parameter 'noise': must be >= 0, got -2");
  EXPECT_EQ(ErrorOf({{"threshold", "automatic"}}),
            "parameter 'threshold': expected a number, got \"automatic\"");
  EXPECT_EQ(ErrorOf(nlohmann::json::array()), "parameters: expected an object, got []");
  EXPECT_EQ(ErrorOf({{"count", 1e12}}),
            "parameter 'count': expected an integer, got 1000000000000.0");
}

TEST(ParameterTable, ErrorsShowBytesThatAreNotUtf8AsHexEscapes) {
  // A string read from a hostile file may hold bytes that are not UTF-8; the error message must
  // still be built, name the key, show the bytes and be UTF-8 itself (so that it can be written
  // into a JSON results file), instead of throwing nlohmann's type_error while printing them.
  const std::string bad_bytes = "a\xff\xfe\\x";
  EXPECT_EQ(ErrorOf({{"count", bad_bytes}}),
            R"(parameter 'count': expected an integer, got "a\xFF\xFE\\x")");
  EXPECT_EQ(ErrorOf({{"mode", bad_bytes}}),
            R"(parameter 'mode': expected one of "fast", "exact", got "a\xFF\xFE\\x")");
  EXPECT_EQ(ErrorOf(nlohmann::json(bad_bytes)),
            R"(parameters: expected an object, got "a\xFF\xFE\\x")");
  EXPECT_EQ(ErrorOf({{"noise", {"\xc3\xa9", "\xc3"}}}),
            "parameter 'noise': expected an array of 3 numbers, got [\"\xc3\xa9\",\"\\xC3\"]");
  EXPECT_EQ(ErrorOf({{"co\x80unt", 1}}),
            R"(unknown parameter 'co\x80unt' (known: count, rate, mode, noise, threshold, gate, )"
            "strict)");
  EXPECT_EQ(ErrorOf(nlohmann::json::array({nlohmann::json::object({{"k\xe0", "v\xed\xa0\x80"}})})),
            R"(parameters: expected an object, got [{"k\xE0":"v\xED\xA0\x80"}])");
  for (const nlohmann::json& overrides :
       {nlohmann::json{{"count", bad_bytes}}, nlohmann::json{{"co\x80unt", 1}},
        nlohmann::json(bad_bytes)}) {
    const std::string message = ErrorOf(overrides);
    EXPECT_NO_THROW((void)nlohmann::json(message).dump()) << message;
  }
}

TEST(ParameterTable, RejectsNonFiniteNumbers) {
  EXPECT_EQ(ErrorOf({{"rate", std::numeric_limits<double>::infinity()}}),
            "parameter 'rate': not finite");
}

struct Floor {
  double position_std = 0.1;
  double heading_std = 0.01;
};

struct Extras {
  std::string loss = "cauchy";
  std::optional<double> level;
  Eigen::Vector3d q = Eigen::Vector3d(1.0, 2.0, 0.5);
  Floor floor;
  Mode mode = Mode::kExact;
};

const ParameterTable<Extras>& ExtrasTable() {
  using E = Extras;
  static const ParameterTable<E> table({
      StringField<E>(
          "loss", [](auto& p) -> auto& { return p.loss; }),
      OptionalNumberField<E>(
          "level", [](auto& p) -> auto& { return p.level; }, AtLeast(0.0)),
      VectorField<E, 3>(
          "q", [](auto& p) -> auto& { return p.q; }, AtLeast(0.0)),
      StructArrayField<E, Floor>(
          "floor", [](auto& p) -> auto& { return p.floor; },
          {{"position_std", &Floor::position_std}, {"heading_std", &Floor::heading_std}},
          Above(0.0)),
      Fixed(EnumField<E, Mode>("mode", [](auto& p) -> auto& { return p.mode; },
                               {{Mode::kFast, "fast"}, {Mode::kExact, "exact"}}),
            "fixed by the name"),
  });
  return table;
}

std::string ExtrasErrorOf(const nlohmann::json& overrides, Extras& e) {
  try {
    ExtrasTable().Apply(overrides, e);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(ParameterTable, WritesStringsOptionalsVectorsAndStructArrays) {
  EXPECT_EQ(ExtrasTable().ToJson(Extras{}), nlohmann::json::parse(R"({"loss": "cauchy",
      "level": null, "q": [1.0, 2.0, 0.5], "floor": [0.1, 0.01], "mode": "exact"})"));
  Extras e;
  e.level = 2.5;
  EXPECT_EQ(ExtrasTable().ToJson(e)["level"], 2.5);
}

TEST(ParameterTable, ReadsStringsOptionalsVectorsAndStructArrays) {
  Extras e;
  ExtrasTable().Apply(nlohmann::json::parse(R"({"loss": "huber", "level": 3, "q": [0, 4, 5],
      "floor": [0.5, 0.25], "mode": "exact"})"),
                      e);
  EXPECT_EQ(e.loss, "huber");
  ASSERT_TRUE(e.level.has_value());
  EXPECT_EQ(*e.level, 3.0);
  EXPECT_EQ(e.q, Eigen::Vector3d(0.0, 4.0, 5.0));
  EXPECT_EQ(e.floor.position_std, 0.5);
  EXPECT_EQ(e.floor.heading_std, 0.25);
  EXPECT_EQ(e.mode, Mode::kExact);
  Extras back;
  ExtrasTable().Apply(ExtrasTable().ToJson(e), back);
  EXPECT_EQ(ExtrasTable().ToJson(back), ExtrasTable().ToJson(e));
  ExtrasTable().Apply({{"level", nullptr}}, e);
  EXPECT_FALSE(e.level.has_value());
}

TEST(ParameterTable, FixedRowAcceptsOnlyTheCurrentValue) {
  Extras e;
  e.mode = Mode::kFast;
  EXPECT_EQ(ExtrasErrorOf({{"mode", "fast"}}, e), "");
  EXPECT_EQ(e.mode, Mode::kFast);
  EXPECT_EQ(ExtrasErrorOf({{"mode", "exact"}}, e),
            "parameter 'mode': fixed by the name: expected \"fast\", got \"exact\"");
  EXPECT_EQ(e.mode, Mode::kFast);
  EXPECT_EQ(ExtrasErrorOf({{"mode", "slow"}}, e),
            "parameter 'mode': expected one of \"fast\", \"exact\", got \"slow\"");
}

TEST(ParameterTable, ExtrasErrorsNameTheKeyAndLeaveTheValueUnchanged) {
  Extras e;
  EXPECT_EQ(ExtrasErrorOf({{"loss", 1}}, e), "parameter 'loss': expected a string, got 1");
  EXPECT_EQ(ExtrasErrorOf({{"level", -1}}, e), "parameter 'level': must be >= 0, got -1");
  EXPECT_EQ(ExtrasErrorOf({{"level", "high"}}, e),
            "parameter 'level': expected a number, got \"high\"");
  EXPECT_EQ(ExtrasErrorOf({{"q", {1, 2}}}, e),
            "parameter 'q': expected an array of 3 numbers, got [1,2]");
  EXPECT_EQ(ExtrasErrorOf({{"q", {1, 2, -3}}}, e), "parameter 'q': must be >= 0, got -3");
  EXPECT_EQ(ExtrasErrorOf({{"floor", {0.5}}}, e),
            "parameter 'floor': expected [position_std, heading_std], got [0.5]");
  EXPECT_EQ(ExtrasErrorOf({{"floor", {0.5, 0}}}, e), "parameter 'floor': must be > 0, got 0");
  EXPECT_EQ(ExtrasTable().ToJson(e), ExtrasTable().ToJson(Extras{}));
}

TEST(ParameterTable, StringRowRefusesTextThatIsNotUtf8) {
  // Accepted, such a string would make the table's own ToJson (a run's config.json) throw later.
  Extras e;
  EXPECT_EQ(ExtrasErrorOf({{"loss", "hub\xe9r"}}, e),
            R"(parameter 'loss': expected UTF-8 text, got "hub\xE9r")");
  EXPECT_EQ(e.loss, "cauchy");
  EXPECT_NO_THROW((void)ExtrasTable().ToJson(e).dump());
  EXPECT_EQ(ExtrasErrorOf({{"loss", "gr\xc3\xbcn"}}, e), "");
  EXPECT_EQ(e.loss, "gr\xc3\xbcn");
  EXPECT_EQ(ExtrasErrorOf({{"mode", "\xff"}}, e),
            R"(parameter 'mode': expected one of "fast", "exact", got "\xFF")");
}

// A table whose rows are used only in some modes: `depth` with mode "exact", `spare` unless
// `count` is 0, `both` only when both hold.
struct Moded {
  std::string mode = "fast";
  int count = 1;
  int depth = 4;
  int spare = 2;
  int both = 0;
};

const ParameterTable<Moded>& ModedTable() {
  using M = Moded;
  static const ParameterTable<M> table({
      StringField<M>(
          "mode", [](auto& p) -> auto& { return p.mode; }),
      IntField<M>(
          "count", [](auto& p) -> auto& { return p.count; }),
      IntField<M>(
          "depth", [](auto& p) -> auto& { return p.depth; })
          .Means("search depth")
          .UsedOnlyWith("mode", {"exact", "deep"}),
      IntField<M>(
          "spare", [](auto& p) -> auto& { return p.spare; })
          .UsedOnlyWithout("count", 0),
      IntField<M>(
          "both", [](auto& p) -> auto& { return p.both; })
          .UsedOnlyWith("mode", {"exact"})
          .UsedOnlyWithout("count", 0),
  });
  return table;
}

// The error of applying `overrides` to the defaults and checking their use ("" when none).
std::string UseError(const nlohmann::json& overrides, Moded baseline = {}) {
  Moded resolved = baseline;
  try {
    ModedTable().Apply(overrides, resolved);
    ModedTable().RequireUsed(overrides, baseline, resolved);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ParameterTable, RefusesAParameterWithoutEffectInTheChosenMode) {
  EXPECT_EQ(UseError({{"depth", 5}}),
            "parameter 'depth' has no effect with mode=fast; it is used only with mode=exact or "
            "deep (set that too, or drop 'depth')");
  EXPECT_EQ(UseError({{"depth", 5}, {"mode", "deep"}}), "");
  EXPECT_EQ(UseError({{"spare", 3}, {"count", 0}}),
            "parameter 'spare' has no effect with count=0; it is used only with count other than "
            "0 (set that too, or drop 'spare')");
  EXPECT_EQ(UseError({{"spare", 3}}), "");
  // Every condition of a row must hold.
  EXPECT_NE(UseError({{"both", 1}, {"mode", "exact"}, {"count", 0}}).find("count other than 0"),
            std::string::npos);
  EXPECT_NE(UseError({{"both", 1}}).find("mode=exact"), std::string::npos);
  EXPECT_EQ(UseError({{"both", 1}, {"mode", "exact"}}), "");
}

TEST(ParameterTable, AcceptsAParameterLeftAtItsValueInAnyMode) {
  // The default (or the value before the overrides, e.g. a recorded configuration read back)
  // changes nothing, so it is accepted in any mode.
  EXPECT_EQ(UseError({{"depth", 4}}), "");
  EXPECT_EQ(UseError(ModedTable().ToJson(Moded{})), "");
  Moded baseline;
  baseline.depth = 9;
  EXPECT_EQ(UseError({{"depth", 9}}, baseline), "");
  EXPECT_NE(UseError({{"depth", 4}}, baseline), "");
}

TEST(ParameterTable, DescribesTheModeARowIsUsedIn) {
  const std::vector<FieldDescription> rows = ModedTable().Descriptions();
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0].used_only_with, "");
  EXPECT_EQ(rows[2].used_only_with, "mode=exact or deep");
  EXPECT_EQ(rows[3].used_only_with, "count other than 0");
  EXPECT_EQ(rows[4].used_only_with, "mode=exact and count other than 0");
}

}  // namespace
}  // namespace phdslam::params
