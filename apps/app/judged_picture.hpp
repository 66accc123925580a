#pragma once
// Pictures of judged grasps: the true scene seen by its camera, with each judged gripper
// coloured by its outcome (evaluate --png, and the judged study's figures).
#include <opencv2/core.hpp>

#include <span>
#include <string>
#include <vector>

#include "uwgrasp/eval/judge.hpp"
#include "uwgrasp/eval/summary.hpp"
#include "uwgrasp/viz/picture.hpp"

namespace uwgrasp::app {

// Green holds, amber closes without force closure, red collides, greys and blues for the rest.
Rgb8 outcome_colour(eval::Outcome o);

// The truth rendered by its camera (perfect sensor, clear water) with the grippers at `poses`
// (T_WG, best first) coloured by the outcome of `judgements` at mu_ref, the best-ranked drawn
// thicker, a cross at each contact, and a key; framed on the target's visible surface.
cv::Mat judged_picture(const sim::World& world, const eval::Camera& camera, const grasp::Gripper& g,
                       std::span<const Pose> poses, std::span<const eval::Judgement> judgements,
                       int target, double mu_ref, const viz::Picture& pic, const viz::View& view = {});

}  // namespace uwgrasp::app
