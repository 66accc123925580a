// uwgrasp evaluate --truth TRUTH.yaml --grasps GRASPS.json: judges a detector's grasps against
// the simulated truth (eval/judge.hpp) - collision with the full objects and the seafloor, the
// closing of the pads, force closure per friction coefficient, robustness of the top-1 - and
// prints a verdict per grasp with graspnet-style metrics; --json writes them.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "app/common.hpp"
#include "commands.hpp"
#include "app/judged_picture.hpp"
#include "app/simulation.hpp"
#include "uwgrasp/core/error.hpp"
#include "uwgrasp/eval/evaluate.hpp"
#include "uwgrasp/io/config_schema.hpp"
#include "uwgrasp/io/grasps_json.hpp"
#include "uwgrasp/io/scene_yaml.hpp"

namespace uwgrasp::app {

namespace {
using nlohmann::json;

struct EvaluateOptions {
  CommonOptions common;
  std::string truth, grasps, object, json_out, png, mu = "0.2,0.3,0.4,0.6,0.8";
  double reference_mu = 0.4;
  std::int64_t top = 10, robust = 25;
};

std::vector<double> parse_mu(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size()) throw Error("--mu: '" + item + "' is not a number");
    out.push_back(v);
  }
  return out;
}

std::string object_name(const sim::Scene& s, int object) {
  if (object == sim::kSeafloorObject) return "seafloor";
  if (object < 0 || std::size_t(object) >= s.objects.size()) return "nothing";
  return s.objects[std::size_t(object)].name;
}

int target_index(const sim::Scene& s, const std::string& name, const std::string& truth) {
  for (std::size_t i = 0; i < s.objects.size(); ++i)
    if (name.empty() ? s.objects[i].interest : s.objects[i].name == name) return int(i);
  if (!name.empty()) throw Error(truth + ": no object named '" + name + "'");
  throw Error(truth + ": no object of interest; name the target with --object");
}

std::string detail(const eval::Judgement& j, const sim::Scene& s) {
  if (j.verdict == eval::Verdict::collision)
    return grasp::part_name(grasp::Part(j.part)) + std::string(j.inside ? " inside " : " in ") + object_name(s, j.object) +
           (j.inside ? "" : j.visible ? " (a surface the camera saw)" : " (a surface the camera did not see)");
  if (j.verdict == eval::Verdict::other_object) return "touches " + object_name(s, j.object) + " first";
  return "";
}

json judgement_json(const eval::Judgement& j, const io::GraspList::Entry& g, const eval::SummaryConfig& sc,
                    const sim::Scene& s) {
  json o = {{"rank", g.rank}, {"score", g.score}, {"verdict", eval::verdict_name(j.verdict)},
            {"outcome", eval::outcome_name(eval::outcome(j, sc.reference_mu))}};
  json holds = json::object();
  for (const double mu : sc.mu) holds[io::shortest(mu)] = j.holds(mu);
  o["holds"] = holds;
  const auto vec = [](const Eigen::Vector3d& v) { return json{v.x(), v.y(), v.z()}; };
  if (j.verdict == eval::Verdict::collision) {
    o["part"] = grasp::part_name(grasp::Part(j.part));
    o["object"] = object_name(s, j.object);
    o["visible"] = j.visible;
    o["inside"] = j.inside;
  }
  if (j.verdict == eval::Verdict::other_object) o["object"] = object_name(s, j.object);
  if (j.verdict == eval::Verdict::closes || j.verdict == eval::Verdict::too_wide ||
      j.verdict == eval::Verdict::too_narrow)
    o["width"] = j.width;
  if (j.verdict == eval::Verdict::closes) {
    o["contacts"] = {vec(j.contacts[0]), vec(j.contacts[1])};
    o["normals"] = {vec(j.normals[0]), vec(j.normals[1])};
    o["mu_min"] = std::isfinite(j.mu_min) ? json(j.mu_min) : json(nullptr);
  }
  return o;
}

void print(const eval::Evaluation& e, const io::GraspList& list, const sim::Scene& s,
           const EvaluateOptions& o, const eval::SummaryConfig& sc, const eval::RobustConfig& rc) {
  std::printf("  rank    score  verdict            width mm  mu_min  detail\n");
  for (std::size_t i = 0; i < e.judgements.size(); ++i) {
    const eval::Judgement& j = e.judgements[i];
    std::printf("  %4zu %8.3f  %-18s", list.grasps[i].rank, list.grasps[i].score,
                eval::outcome_name(eval::outcome(j, o.reference_mu)));
    if (j.verdict == eval::Verdict::closes || j.verdict == eval::Verdict::too_wide || j.verdict == eval::Verdict::too_narrow)
      std::printf(" %8.1f", j.width * 1000);
    else
      std::printf(" %8s", "-");
    if (j.verdict == eval::Verdict::closes && std::isfinite(j.mu_min)) std::printf("  %6.3f", j.mu_min);
    else std::printf("  %6s", j.verdict == eval::Verdict::closes ? "inf" : "-");
    std::printf("  %s\n", detail(j, s).c_str());
  }
  std::printf("top-1 success:");
  for (std::size_t m = 0; m < sc.mu.size(); ++m)
    std::printf("%s mu %.2g %s", m ? " |" : "", sc.mu[m], e.summary.top1[m] ? "yes" : "no");
  std::printf("\nprecision@1/5/10 at mu %.2g: %.2f %.2f %.2f\n", o.reference_mu, e.summary.precision[0],
              e.summary.precision[1], e.summary.precision[2]);
  std::printf("AP (mu %s, k 1-%zu): %.3f\n", o.mu.c_str(), sc.top, e.summary.ap);
  if (std::isfinite(e.robust_top1))
    std::printf("robust success of the top-1 at mu %.2g (%u poses, sigma %.0f mm, %.0f deg): %.2f\n", rc.mu,
                rc.samples, rc.sigma_position * 1000, rc.sigma_angle * 180 / std::numbers::pi, e.robust_top1);
  std::printf("outcomes at mu %.2g:", o.reference_mu);
  for (int k = 0; k < eval::kOutcomes; ++k)
    if (e.summary.outcomes[std::size_t(k)] > 0)
      std::printf(" %s %zu", eval::outcome_name(eval::Outcome(k)), e.summary.outcomes[std::size_t(k)]);
  std::printf("%s\n", e.summary.judged == 0 ? " none (no grasp to judge: a failure)" : "");
}

json summary_json(const eval::Evaluation& e, const eval::SummaryConfig& sc, const eval::RobustConfig& rc) {
  json top1 = json::object(), ap = json::object();
  for (std::size_t m = 0; m < sc.mu.size(); ++m) {
    top1[io::shortest(sc.mu[m])] = bool(e.summary.top1[m]);
    ap[io::shortest(sc.mu[m])] = e.summary.ap_per_mu[m];
  }
  json outcomes = json::object();
  for (int k = 0; k < eval::kOutcomes; ++k)
    outcomes[eval::outcome_name(eval::Outcome(k))] = e.summary.outcomes[std::size_t(k)];
  return {{"top1_success", top1},
          {"precision_at", {{"1", e.summary.precision[0]}, {"5", e.summary.precision[1]}, {"10", e.summary.precision[2]}}},
          {"ap", e.summary.ap},
          {"ap_per_mu", ap},
          {"robust_top1", std::isfinite(e.robust_top1) ? json(e.robust_top1) : json(nullptr)},
          {"robust", {{"samples", rc.samples}, {"sigma_position", rc.sigma_position},
                      {"sigma_angle", rc.sigma_angle}, {"mu", rc.mu}}},
          {"outcomes", outcomes},
          {"judged", e.summary.judged}};
}

int run_evaluate(const EvaluateOptions& o) {
  const Session session = open_session(o.common);
  eval::SummaryConfig sc;
  sc.mu = parse_mu(o.mu);
  sc.reference_mu = o.reference_mu;
  sc.top = std::size_t(o.top);
  eval::check_summary(sc);
  eval::RobustConfig rc;
  rc.samples = std::uint32_t(o.robust);
  rc.mu = o.reference_mu;
  const io::Truth truth = io::load_truth(o.truth);
  const io::GraspList list = io::read_grasp_list(o.grasps, o.object);
  const int target = target_index(truth.scene, o.object.empty() ? list.object : o.object, o.truth);
  const grasp::Gripper gripper = grasp::make_gripper(list.gripper);
  const sim::World world(truth.scene);
  const eval::Camera camera{truth.info.world_from_camera, truth.info.intrinsics, truth.info.camera.max_range};
  std::vector<Pose> poses;
  for (const auto& g : list.grasps)
    poses.push_back(list.frame == "world" ? g.pose : camera.world_from_camera * g.pose);
  const eval::Evaluation e = eval::evaluate(world, camera, gripper, poses, target, sc, rc, session.config.seed);

  std::printf("truth %s: %zu objects, target %s; %s: %zu grasps (%s frame), gripper %s (%.0f mm open, %.0f mm usable)\n",
              o.truth.c_str(), truth.scene.objects.size(), object_name(truth.scene, target).c_str(),
              o.grasps.c_str(), list.grasps.size(), list.frame.c_str(),
              list.gripper_from_file ? "from the file's config" : "default", gripper.config.max_aperture * 1000.0,
              grasp::max_grasp_width(gripper) * 1000.0);
  print(e, list, truth.scene, o, sc, rc);
  if (!o.json_out.empty()) {
    json j = {{"uwgrasp_version", UWGRASP_VERSION}, {"truth", o.truth}, {"grasps", o.grasps},
              {"target", object_name(truth.scene, target)}, {"mu", sc.mu}, {"reference_mu", sc.reference_mu},
              {"top", sc.top}, {"seed", session.config.seed}, {"summary", summary_json(e, sc, rc)}};
    j["judgements"] = json::array();
    for (std::size_t i = 0; i < e.judgements.size(); ++i)
      j["judgements"].push_back(judgement_json(e.judgements[i], list.grasps[i], sc, truth.scene));
    io::write_json(o.json_out, j);
  }
  if (!o.png.empty()) {
    viz::Picture pic;
    pic.title = "uwgrasp evaluate: " + o.grasps + " on " + object_name(truth.scene, target);
    pic.legend.push_back("grippers coloured by the judged outcome at mu " + io::shortest(sc.reference_mu) +
                         "; the best-ranked grasp drawn thick; crosses at the contacts");
    write_png(o.png, judged_picture(world, camera, gripper, poses, e.judgements, target, sc.reference_mu, pic));
  }
  return 0;
}
}  // namespace

void add_evaluate_command(CLI::App& app, std::vector<std::pair<CLI::App*, Runner>>& runners) {
  auto* cmd = app.add_subcommand("evaluate", "Judge grasps against the simulated truth (full object shapes)");
  auto o = std::make_shared<EvaluateOptions>();
  cmd->add_option("--truth", o->truth, "truth.yaml written by simulate or demo")->required();
  cmd->add_option("--grasps", o->grasps, "grasps.json of any detector (documented fields)")->required();
  cmd->add_option("--object", o->object, "The target object (a demo file's object; default: the truth's object of interest)");
  cmd->add_option("--mu", o->mu, "Friction coefficients, comma-separated")->capture_default_str();
  cmd->add_option("--reference-mu", o->reference_mu, "Friction coefficient of success, precision@k and robustness")
      ->capture_default_str();
  cmd->add_option("--top", o->top, "Grasps judged (and k of AP)")->check(CLI::Range(1, 100000))->capture_default_str();
  cmd->add_option("--robust", o->robust, "Perturbed poses for the top-1's robust force closure (0: off)")
      ->check(CLI::Range(0, 100000))->capture_default_str();
  cmd->add_option("--json", o->json_out, "Write the verdicts and metrics as JSON");
  cmd->add_option("--png", o->png, "Draw the judged grippers on the true scene, coloured by outcome");
  add_common(*cmd, o->common);
  runners.emplace_back(cmd, [o] { return run_evaluate(*o); });
}

}  // namespace uwgrasp::app
