#pragma once
// A camera behind a flat port (thesis 3.2): the camera's rays leave the housing's air through a
// glass plate perpendicular to the optical axis and bend at both of its faces by Snell's law,
// n1 sin(a1) = n2 sin(a2). In water the rays no longer meet in one centre of projection, so a
// pinhole model calibrated in air is wrong under water (3.2.1). The geometry is shared by the
// simulator (rendering through the port) and the camera module (the Pinax correction).
// Camera optical frame C: z forward (the port's normal), x right, y down.
#include <Eigen/Core>
#include <optional>

namespace uwgrasp {

struct FlatPort {
  double distance = 0.01;   // camera centre to the glass's inner face, along z, m
  double thickness = 0.01;  // glass, m
  double n_air = 1.0;       // inside the housing
  double n_glass = 1.49;    // acrylic (about 1.52 for glass)
  double n_water = 1.34;    // sea water at ~15 C (1.333 fresh)
};

// Throws Error naming the field (port.distance, port.thickness, port.n_*) for a negative or
// non-finite length, or a refractive index outside [1, 3].
void check_port(const FlatPort& port);

// A ray in C: origin and direction (not necessarily unit).
struct PortRay {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

// The in-water ray that the camera's in-air ray `direction` (from C's origin, z > 0) becomes
// after both faces of the port: its origin on the glass's outer face, its direction scaled to
// z = 1. nullopt when the ray does not reach the port (z <= 0) or is totally reflected.
std::optional<PortRay> refract_through_port(const FlatPort& port, const Eigen::Vector3d& direction);

// The in-air direction (z = 1) from C's origin whose ray, refracted by the port, passes through
// the in-water point `p` (C, beyond the port). Exact: the ray stays in the plane through the
// optical axis and p, where the radial offset it reaches at p's depth grows monotonically with
// its angle; solved by bisection to 1e-12 rad. nullopt when p is not beyond the port.
std::optional<Eigen::Vector3d> direction_to(const FlatPort& port, const Eigen::Vector3d& p);

// Snell's law for a unit direction d crossing a surface with unit normal n (pointing back
// against d) from index n1 into n2; nullopt on total internal reflection.
std::optional<Eigen::Vector3d> refract(const Eigen::Vector3d& d, const Eigen::Vector3d& n, double n1, double n2);

}  // namespace uwgrasp
