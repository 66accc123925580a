#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <sstream>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/io/config.hpp"

namespace uwgrasp::io {

namespace {
std::string error_of(const std::string& yaml, const std::vector<std::string>& sets = {}) {
  try {
    parse_config(yaml, "test.yaml", sets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Config, DefaultYamlMirrorsTheCompiledDefaults) {
  std::ifstream f(std::string(UWGRASP_SOURCE_DIR) + "/config/default.yaml");
  ASSERT_TRUE(f) << "config/default.yaml missing";
  std::stringstream s;
  s << f.rdbuf();
  const Config from_file = parse_config(s.str(), "default.yaml");
  EXPECT_EQ(to_yaml(from_file), to_yaml(Config{}));
  EXPECT_EQ(to_json(from_file), to_json(Config{}));
}

TEST(Config, ValuesRoundTripThroughYaml) {
  Config c;
  c.seed = 12345678901234ULL;
  c.preprocess.voxel.leaf = 0.004f;
  c.preprocess.plane.enabled = false;
  c.segment.object.by = segment::ObjectBy::largest;
  c.segment.object.color = "yellow";
  const Config back = parse_config(to_yaml(c), "x");
  EXPECT_EQ(to_yaml(back), to_yaml(c));
  EXPECT_EQ(back.segment.object.by, segment::ObjectBy::largest);
  EXPECT_FLOAT_EQ(back.preprocess.voxel.leaf, 0.004f);
  EXPECT_EQ(to_json(c)["preprocess"]["voxel"]["leaf"], 0.004);
}

TEST(Config, ErrorsNameFileAndKey) {
  EXPECT_NE(error_of("preprocess:\n  voxl:\n    leaf: 1\n").find("unknown key 'preprocess.voxl'"), std::string::npos);
  EXPECT_NE(error_of("preprocess:\n  voxel:\n    leaf: abc\n").find("preprocess.voxel.leaf: expected a number"), std::string::npos);
  EXPECT_NE(error_of("preprocess:\n  voxel:\n    leaf: -1\n").find("out of range"), std::string::npos);
  EXPECT_NE(error_of("segment:\n  region:\n    k: 2.5\n").find("expected an integer"), std::string::npos);
  EXPECT_NE(error_of("segment:\n  object:\n    by: smallest\n").find("not one of"), std::string::npos);
  EXPECT_NE(error_of("preprocess:\n  plane:\n    refine: maybe\n").find("true or false"), std::string::npos);
  EXPECT_NE(error_of("seed: -3\n").find("seed"), std::string::npos);
  EXPECT_NE(error_of("preprocess: [1, 2]\n").find("expected a section"), std::string::npos);
  EXPECT_NE(error_of("a: [\n").find("not valid YAML"), std::string::npos);
  EXPECT_NE(error_of("").find(""), std::string::npos);
  EXPECT_EQ(error_of(""), "");  // an empty file means all defaults
  for (const auto& e : {error_of("preprocess:\n  voxl: 1\n"), error_of("seed: x")})
    EXPECT_NE(e.find("test.yaml"), std::string::npos) << e;
}

TEST(Config, SetOverridesApplyAfterTheFile) {
  const Config c = parse_config("preprocess:\n  voxel:\n    leaf: 0.01\n", "x",
                                {"preprocess.voxel.leaf=0.02", "segment.region.k=12", "seed=7"});
  EXPECT_FLOAT_EQ(c.preprocess.voxel.leaf, 0.02f);
  EXPECT_EQ(c.segment.region.k, 12u);
  EXPECT_EQ(c.seed, 7u);
  EXPECT_NE(error_of("", {"preprocess.voxel.lef=1"}).find("unknown key 'preprocess.voxel.lef'"), std::string::npos);
  EXPECT_NE(error_of("", {"novalue"}).find("section.key=value"), std::string::npos);
  EXPECT_NE(error_of("", {"segment.region.k=-1"}).find("--set"), std::string::npos);
  // Robust mode offers only measured grasps: measuring none would offer none, silently.
  for (const char* zero : {"grasp.score.robust.samples=0", "grasp.score.robust.candidates=0"})
    EXPECT_NE(error_of("", {zero}).find("is out of range [1, "), std::string::npos) << zero;
}

// level_from_floor was a bool before "auto": YAML's true / false keep their meaning.
TEST(Config, LevelFromFloorTakesAutoAndTheOldBooleans) {
  using L = grasp::FrameConfig::Level;
  EXPECT_EQ(Config{}.grasp.frames.level_from_floor, L::automatic);
  const std::pair<const char*, L> cases[] = {
      {"auto", L::automatic}, {"true", L::floor}, {"false", L::attitude}};
  for (const auto& [text, level] : cases) {
    const Config c = parse_config("", "x", {std::string("grasp.frames.level_from_floor=") + text});
    EXPECT_EQ(c.grasp.frames.level_from_floor, level) << text;
    EXPECT_EQ(parse_config(to_yaml(c), "x").grasp.frames.level_from_floor, level) << text;
  }
  EXPECT_NE(error_of("grasp:\n  frames:\n    level_from_floor: yes\n")
                .find("grasp.frames.level_from_floor: 'yes' is not one of auto, true, false"),
            std::string::npos);
}

TEST(Config, MissingFile) {
  EXPECT_THROW(load_config("/nonexistent/uwgrasp.yaml"), Error);
  EXPECT_EQ(load_config("", {"threads=2"}).threads, 2u);
}

}  // namespace uwgrasp::io

namespace uwgrasp::io {

// config/thesis_*.yaml reproduce Table 8.5.
TEST(Config, ThesisPresetsReproduceTable85) {
  struct Row {
    const char* file;
    grasp::SamplerKind sampler;
    double w_i, max_inliers;
  };
  for (const Row& r : {Row{"barbell", grasp::SamplerKind::normal, 2.0, 135},
                       Row{"circle", grasp::SamplerKind::uniform, 1.0, 135},
                       Row{"cross", grasp::SamplerKind::uniform, 1.0, 250}}) {
    SCOPED_TRACE(r.file);
    const Config c = load_config(std::string(UWGRASP_SOURCE_DIR) + "/config/thesis_" + r.file + ".yaml");
    const auto& s = c.grasp.score;
    EXPECT_EQ(c.grasp.sampler.kind, r.sampler);
    EXPECT_EQ(c.grasp.sampler.samples, 3000u);
    EXPECT_NEAR(c.grasp.sampler.sigma_theta.x(), std::numbers::pi / 4, 1e-15);
    EXPECT_EQ(c.grasp.sampler.alpha_p, Eigen::Vector3d::Ones());
    EXPECT_EQ(s.weights.normal, 1.0);
    EXPECT_EQ(s.weights.orientation, 1.0);
    EXPECT_EQ(s.weights.contact, 1.0);
    EXPECT_EQ(s.weights.inliers, r.w_i);
    EXPECT_EQ(s.orientation.form, grasp::OrientationForm::thesis);
    EXPECT_EQ(s.orientation.roll, 0.45);
    EXPECT_EQ(s.orientation.pitch, 0.45);
    EXPECT_EQ(s.orientation.yaw, 0.1);
    EXPECT_EQ(s.inlier_mode, grasp::InlierMode::fixed);
    EXPECT_EQ(s.max_inliers, r.max_inliers);
  }
}

}  // namespace uwgrasp::io

namespace uwgrasp::io {

// config/vehicle/bluerov2_heavy.yaml is the defaults' sourced twin: loading it changes nothing,
// and its thrusters reproduce von Benzon's allocation matrix (tests/vehicle checks K itself).
TEST(Config, VehicleFileIsTheDefaultVehicle) {
  const Config c = load_config(std::string(UWGRASP_SOURCE_DIR) + "/config/vehicle/bluerov2_heavy.yaml");
  EXPECT_EQ(to_yaml(c), to_yaml(Config{}));
  ASSERT_EQ(c.vehicle.params.thrusters.size(), 8u);
  const auto heavy = vehicle::heavy_thrusters();
  for (std::size_t i = 0; i < 8; ++i) {
    EXPECT_EQ(c.vehicle.params.thrusters[i].position, heavy[i].position) << "t" << i + 1;
    EXPECT_EQ(c.vehicle.params.thrusters[i].direction, heavy[i].direction) << "t" << i + 1;
  }
}

TEST(Config, VehicleErrorsNameTheField) {
  const auto has = [](const std::string& e, const char* what) {
    return e.find(what) != std::string::npos;
  };
  EXPECT_TRUE(has(error_of("vehicle:\n  mass: 0\n"), "vehicle.mass"));
  EXPECT_TRUE(has(error_of("vehicle:\n  inertia: [0.2, -1, 0.3]\n"), "vehicle.inertia"));
  EXPECT_TRUE(has(error_of("vehicle:\n  thrust:\n    min: 10\n"), "vehicle.thrust.min"));
  EXPECT_TRUE(has(error_of("vehicle:\n  thrusters:\n    t9:\n      position: [0, 0, 0]\n"), "vehicle.thrusters.t9"));
  EXPECT_TRUE(has(error_of("vehicle:\n  added_mass:\n    surge: -1\n"), "vehicle.added_mass.surge"));
  EXPECT_TRUE(has(error_of("grasp:\n  reach:\n    hull_size: [0, 1, 1]\n"), "grasp.reach.hull_size"));
  EXPECT_TRUE(has(error_of("vehicle:\n  control:\n    dt: 0\n"), "vehicle.control.dt"));
  const Config c = parse_config("vehicle:\n  current: [0.2, 0, 0]\n  thrusters:\n    t3:\n      direction: [0, 1, 0]\n", "x");
  EXPECT_EQ(c.vehicle.current, Eigen::Vector3d(0.2, 0, 0));
  EXPECT_EQ(c.vehicle.params.thrusters[2].direction, Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(c.vehicle.params.thrusters[0].direction, vehicle::heavy_thrusters()[0].direction);
}

}  // namespace uwgrasp::io
