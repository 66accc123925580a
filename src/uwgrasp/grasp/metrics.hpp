#pragma once
// Grasp quality metrics (thesis chapter 6), each in [0, 1], and the weighted total (eq. 6.8).
#include <Eigen/Core>
#include <cstddef>

namespace uwgrasp::grasp {

// Eq. 6.1/6.2 with the erratum of ARCHITECTURE.md: the cosine is the normalised dot product,
// q = |a.b| / (|a| |b|). 0 when either vector is zero.
double alignment(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

// q_n (6.2): the approach direction against the surface normal of the closing-region point
// nearest the gripper position.
inline double normal_score(const Eigen::Vector3d& approach, const Eigen::Vector3d& surface_normal) {
  return alignment(approach, surface_normal);
}

// Eq. 6.3 per angle. thesis: 1 - |sin a|, which rises again past pi/2; monotone (default, 9.2):
// 1 - |sin a| for |a| <= pi/2, else 0. Angles are wrapped to (-pi, pi] first.
enum class OrientationForm { monotone, thesis };
double orientation_term(double angle, OrientationForm form);

struct OrientationConfig {
  OrientationForm form = OrientationForm::monotone;
  // w_phi, w_theta, w_psi of eq. 6.4 (Table 8.5); normalised to sum to 1 when used.
  double roll = 0.45, pitch = 0.45, yaw = 0.1;
};
// q_o (eq. 6.4) of a vehicle attitude (roll, pitch, yaw). Throws Error when the weights sum to 0.
double orientation_score(const Eigen::Vector3d& rpy, const OrientationConfig& cfg);

// q_cl, q_cr (6.4): the connecting line between the contacts against each contact's normal.
// When the contacts are closer than `min_separation` along the line (one point, or a single
// layer), the line is undefined and the closing direction stands in for it.
struct ContactScores {
  double left = 0.0, right = 0.0;
  Eigen::Vector3d line = Eigen::Vector3d::Zero();  // unit connecting line used
};
ContactScores contact_scores(const Eigen::Vector3d& left, const Eigen::Vector3d& right,
                             const Eigen::Vector3d& left_normal,
                             const Eigen::Vector3d& right_normal, const Eigen::Vector3d& closing,
                             double min_separation = 1e-3);

// Antipodal test for Coulomb friction mu (eq. 6.6, Murray et al.; the discussion of 9.2): the
// connecting line must lie inside both friction cones, i.e. its angle to each contact normal
// (either sense: a one-sided cloud cannot tell inside from outside) is at most atan(mu).
struct Antipodal {
  bool ok = false;
  double mu_required = 0.0;  // the smallest mu for which the grasp is antipodal
};
Antipodal antipodal(const ContactScores& contacts, double mu);

// The smallest mu for which contacts c with outward normals n, on the left and right of a
// closing, are in force closure (Nguyen's two-contact condition, the friction-cone form of 6.4):
// tan of the larger angle between the contact line and either inward normal; +inf when an angle
// reaches 90 degrees. `closing` stands in for the line when the contacts coincide.
double force_closure_mu(const Eigen::Vector3d& c_left, const Eigen::Vector3d& n_left,
                        const Eigen::Vector3d& c_right, const Eigen::Vector3d& n_right,
                        const Eigen::Vector3d& closing);

// q_i (eq. 6.7), clipped to 1.
double inlier_score(std::size_t inliers, double max_inliers);

// Maximum inliers derived from the gripper (6.5): `volume` is the thesis's closing-region volume
// over the voxel volume; `surface` is the largest cross-section of the closing region over the
// voxel face, the most a one-sided surface can put in it.
double max_inliers_volume(const Eigen::Vector3f& closing_size, double leaf);
double max_inliers_surface(const Eigen::Vector3f& closing_size, double leaf);

struct Weights {
  double normal = 1.0, orientation = 1.0, contact = 1.0, inliers = 1.0;  // Table 8.5
  // q_v, what holding the attitude costs the thrusters (see ScoreConfig::hold_cost); 0 keeps the
  // thesis's q_tot, which scores attitude by q_o alone.
  double vehicle = 0.0;
};
struct Scores {
  double normal = 0, orientation = 0, contact_left = 0, contact_right = 0, inliers = 0;
  double vehicle = 0;  // q_v = 1 - thruster utilisation of the hold; 0 when no model was given
  double total = 0;
};
// Eq. 6.8 plus the vehicle term: q_tot = w_n q_n + w_o q_o + w_c q_cl + w_c q_cr + w_i q_i + w_v q_v.
double total_score(const Scores& s, const Weights& w);
// Throws Error when a weight is negative or not finite, or all are 0.
void check_weights(const Weights& w);

}  // namespace uwgrasp::grasp
