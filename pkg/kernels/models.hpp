// Capillary bridge models as pure functions: SI units in and out, angles in radians, no YADE
// types. Forces are magnitudes of the attraction along the line of centres (>= 0); the gap a is
// the surface separation (>= 0).
//
// Every model is evaluated in two steps: make_bridge() validates the inputs and computes the
// per-bridge invariants once (e.g. Willett's f1..f4, Richefeu's lambda, the rupture distance);
// bridge_force() is the cheap per-step evaluation. The one-shot functions at the end of this
// header (force(), rupture_distance()) go through the same two steps, so every formula exists
// in one place only.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

namespace capillary {

enum class Model {
	weigert,             // Gladkyy2014 eq. (5), (A2)-(A7); Weigert & Ripperger 1999
	willett_full,        // Gladkyy2014 eq. (6), (7), (B1)-(B4); Willett et al. 2000
	willett_reduced,     // Gladkyy2014 eq. (6), (8); Willett et al. 2000 eq. (12)
	rabinovich,          // Gladkyy2014 eq. (9)-(11), with the sine term; Rabinovich et al. 2005
	rabinovich_lambert,  // Gladkyy2014 eq. (9), (10), (12); Lambert et al. 2008
	richefeu,            // Richefeu2008 eq. (4), (5), (7), (10), (11)
	soulie,              // Soulie et al. 2006 (coefficients as printed there, see models.cpp)
	linear_irreversible, // Roy et al. eq. (16), (17), calibration of their section 4.2
	young_laplace_table  // exact Young-Laplace bridge, tabulated (young_laplace_table.hpp)
};

enum class Rupture {
	lian,           // (1 + theta/2) V^(1/3): Lian 1993, Richefeu2008 eq. (6), Roy eq. (15)
	willett,        // Gladkyy2014 eq. (2), Elskamp2018 eq. (31)
	willett_elskamp // unequal spheres and angles: Elskamp2018 eq. (32)
};

struct ModelInfo {
	Model       model;
	const char* name;
	const char* reference;
	bool        monotone; // force non-increasing in the gap over the whole bridge
};
struct RuptureInfo {
	Rupture     rule;
	const char* name;
	const char* reference;
};
// The one table of models and rupture rules (names are the user-facing identifiers).
const std::vector<ModelInfo>&   models();
const std::vector<RuptureInfo>& rupture_rules();
Model                           model_from_name(const std::string& name);   // throws std::invalid_argument
Rupture                         rupture_from_name(const std::string& name); // throws std::invalid_argument
const char*                     name_of(Model m);
const char*                     name_of(Rupture r);
std::string                     model_names();   // "weigert, willett_full, ..." for error messages
std::string                     rupture_names();

constexpr double wall_radius = std::numeric_limits<double>::infinity();

// Inputs of one bridge. R2 = wall_radius (infinity) means a sphere-wall (plane) bridge.
struct BridgeSpec {
	double  R1     = 0;     // [m] sphere radius
	double  R2     = 0;     // [m] sphere radius, or wall_radius
	double  volume = 0;     // [m^3] liquid bridge volume
	double  gamma  = 0;     // [N/m] surface tension
	double  theta1 = 0;     // [rad] contact angle on body 1
	double  theta2 = 0;     // [rad] contact angle on body 2
	Model   model  = Model::willett_full;
	Rupture rupture = Rupture::willett;
	// linear_irreversible only: if both > 0 they are used as given, otherwise they are calibrated
	// from `calibrate_from` by equal maximum force and equal adhesive energy (Roy et al. 4.2).
	double linear_fmax = 0;                       // [N] maximum adhesive force
	double linear_kc   = 0;                       // [N/m] adhesive stiffness
	Model  calibrate_from = Model::willett_full;  // reference model (not linear_irreversible)
};

// Per-bridge invariants, computed once by make_bridge().
struct Bridge {
	Model  model;
	double R;         // [m] effective radius, harmonic mean 2R1R2/(R1+R2) (Gladkyy2014 eq. 1)
	double gamma;     // [N/m]
	double theta;     // [rad] mean contact angle (theta1+theta2)/2 (Elskamp2018, after eq. 15)
	double volume;    // [m^3]
	double rupture;   // [m] gap at which the bridge breaks
	double force0;    // [N] force at contact, F(a = 0)
	std::array<double, 53> k; // model-specific invariants, documented in models.cpp (young_laplace_table uses all)
};

// Validates (std::invalid_argument naming the parameter and its allowed range) and computes the
// invariants. A wall (R2 = infinity) is treated as the Derjaguin-equivalent pair of two equal
// spheres of radius 2*R1, whose harmonic and geometric means are both 2*R1: the sphere-plane
// limit 4*pi*R1*gamma*cos(theta) for every model.
Bridge make_bridge(const BridgeSpec& spec);

// Capillary force [N] at gap a [m]: 0 for a > rupture, F(0) for a <= 0. Never NaN or inf.
double bridge_force(const Bridge& b, double a);

// Rupture distance [m] of a rule for the given pair (R2 may be wall_radius).
double rupture_distance(Rupture rule, double R1, double R2, double volume, double theta1, double theta2);

// One-shot convenience: make_bridge() + bridge_force().
double force(const BridgeSpec& spec, double a);

// Willett's full-model coefficients f1..f4 (Gladkyy2014 eq. B1-B4) for V* = V/R^3, theta [rad].
std::array<double, 4> willett_coefficients(double vstar, double theta);

// Adhesive energy [J] of a bridge: integral of F over [0, rupture].
double adhesive_energy(const Bridge& b);

} // namespace capillary
