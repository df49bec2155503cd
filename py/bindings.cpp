// Python module of the pure capillary kernels (yade_capillary._kernels), re-exported as
// yade_capillary.kernels. Usable in plain python3 and inside yade: plot F(a) without a simulation.
#include "models.hpp"
#include "bonds.hpp"
#include "film.hpp"
#include "transfer.hpp"
#include "viscous.hpp"
#include "young_laplace.hpp"
#include "young_laplace_table.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <optional>

namespace py = pybind11;
using namespace capillary;

namespace {

BridgeSpec spec(const std::string& model, double R1, double R2, double volume, double gamma, double theta,
                std::optional<double> theta2, const std::string& rupture, double linear_fmax, double linear_kc,
                const std::string& calibrate_from, bool extrapolate)
{
	BridgeSpec s;
	s.model          = model_from_name(model);
	s.rupture        = rupture_from_name(rupture);
	try {
		s.calibrate_from = model_from_name(calibrate_from);
	} catch (const std::invalid_argument&) {
		throw std::invalid_argument("calibrate_from = '" + calibrate_from + "' is unknown; allowed: " + model_names());
	}
	s.R1             = R1;
	s.R2             = R2;
	s.volume         = volume;
	s.gamma          = gamma;
	s.theta1         = theta;
	s.theta2         = theta2.value_or(theta);
	s.linear_fmax    = linear_fmax;
	s.linear_kc      = linear_kc;
	s.extrapolate    = extrapolate;
	return s;
}

py::dict bridge_dict(const BridgeSpec& s)
{
	const Pair   p = pair_of(s);
	const Bridge b = make_bridge(s);
	py::dict     d;
	d["model"]        = name_of(b.model());
	d["extrapolated"] = b.extrapolated();
	d["R"]            = p.R;
	d["theta"]        = p.theta;
	d["rupture"]      = b.rupture;
	d["force0"]       = b.force0;
	d["energy"]       = adhesive_energy(b);
	if (const auto* lin = std::get_if<LinearIrreversible>(&b.m)) {
		d["linear_fmax"] = lin->fmax;
		d["linear_kc"]   = lin->kc;
	}
	return d;
}

py::dict domain_dict(const Domain& d)
{
	py::dict out;
	out["vstar_min"] = d.vstar_min, out["vstar_max"] = d.vstar_max, out["theta_max"] = d.theta_max, out["ratio_max"] = d.ratio_max;
	out["wall"] = d.wall, out["equal_angles"] = d.equal_angles, out["source"] = d.source;
	return out;
}

// The argument documentation, with the model and rule names from the one model table.
const std::string& common_args()
{
	static const std::string doc = R"(
    model: one of models() ()" + model_names() + R"()
    R1, R2: sphere radii [m]; R2 = inf for a sphere-wall (plane) bridge
    volume: liquid bridge volume [m^3], > 0
    gamma: surface tension [N/m], > 0
    theta: contact angle [rad] in [0, pi/2) (on sphere 1; also on sphere 2 unless theta2 is given)
    theta2: contact angle on sphere 2 [rad]; the force models use acos((cos theta + cos theta2)/2), the lian and willett rupture rules the mean angle
    rupture: rupture rule, one of rupture_rules() ()" + rupture_names() + R"()
    linear_fmax [N], linear_kc [N/m]: linear_irreversible parameters; both 0 = calibrate from
           calibrate_from by equal maximum force and adhesive energy (Roy et al. 4.2)
    extrapolate: outside the model's domain (models()[i]['domain']) a bridge is refused; True
           evaluates the model at the nearest point of its domain instead, stretched to the
           bridge's rupture distance and scaled by R cos(theta)
Raises ValueError naming the parameter, its value and its allowed range.)";
	return doc;
}

} // namespace

PYBIND11_MODULE(_kernels, m)
{
	m.doc() = "Pure capillary bridge models of yade-capillary (SI units, radians).";

	m.def("models", [] {
		py::list l;
		for (const auto& r : models()) {
			py::dict d;
			d["name"] = r.name, d["reference"] = r.reference, d["monotone"] = r.monotone, d["own_rupture"] = r.own_rupture;
			d["needs_linear"] = r.needs_linear;
			d["domain"] = domain_dict(r.domain);
			l.append(d);
		}
		return l;
	}, "List of every capillary model as a dict: name, reference, monotone (force never grows with the gap), own_rupture "
	   "(the model sets its own range, not the rupture rule) and domain (vstar_min, vstar_max: V* = V/R^3 with R the harmonic "
	   "mean radius, a wall counting as 2 R1 [-]; theta_max [rad]; ratio_max = R_large/R_small [-]; wall: sphere-wall allowed; "
	   "equal_angles; source).");
	m.def("rupture_rules", [] {
		py::list l;
		for (const auto& r : rupture_rules()) l.append(py::make_tuple(r.name, r.reference));
		return l;
	}, "List of (name, reference) for every rupture rule.");

	m.def(
	        "force",
	        [](const std::string& model, py::array_t<double, py::array::c_style | py::array::forcecast> gap, double R1, double R2, double volume, double gamma, double theta,
	           std::optional<double> theta2, const std::string& rupture, double linear_fmax, double linear_kc,
	           const std::string& calibrate_from, bool extrapolate, std::optional<double> range) -> py::object {
		        const Bridge b = make_bridge(spec(model, R1, R2, volume, gamma, theta, theta2, rupture, linear_fmax, linear_kc, calibrate_from, extrapolate));
		        const double upTo = range.value_or(b.rupture);
		        if (!(upTo >= b.rupture && std::isfinite(upTo)))
			        throw py::value_error("range = " + format_value(upTo) + " m is outside the allowed range [rupture, inf) = [" + format_value(b.rupture)
			                              + ", inf) m (finite)");
		        py::array_t<double> out(gap.request().shape);
		        double*             o = out.mutable_data();
		        const double*       g = gap.data();
		        for (py::ssize_t i = 0; i < gap.size(); ++i) {
			        if (std::isnan(g[i])) throw py::value_error("gap is NaN; allowed: any real number [m]");
			        o[i] = bridge_force_within(b, g[i], upTo);
		        }
		        if (gap.ndim() == 0) return py::float_(o[0]);
		        return std::move(out);
	        },
	        py::arg("model"), py::arg("gap"), py::arg("R1"), py::arg("R2"), py::arg("volume"), py::arg("gamma"), py::arg("theta") = 0.0,
	        py::arg("theta2") = py::none(), py::arg("rupture") = "willett", py::arg("linear_fmax") = 0.0, py::arg("linear_kc") = 0.0,
	        py::arg("calibrate_from") = "willett_full", py::arg("extrapolate") = false, py::arg("range") = py::none(),
	        (std::string("Capillary force [N] (attraction > 0) at surface gap(s) `gap` [m] (float or array): 0 beyond the rupture "
	                     "distance, F(0) for gap <= 0. range [m] >= the rupture distance: the gap up to which a bridge lasts under the "
	                     "dynamic rupture rule (Elskamp2018 eq. 33; e.g. dynamic_rupture_distance(...)); beyond the rupture distance the "
	                     "model's formula is continued, floored at 0 (young_laplace_table keeps its force at the rupture distance).")
	         + common_args())
	                .c_str());

	m.def(
	        "bridge",
	        [](const std::string& model, double R1, double R2, double volume, double gamma, double theta, std::optional<double> theta2,
	           const std::string& rupture, double linear_fmax, double linear_kc, const std::string& calibrate_from, bool extrapolate) {
		        return bridge_dict(spec(model, R1, R2, volume, gamma, theta, theta2, rupture, linear_fmax, linear_kc, calibrate_from, extrapolate));
	        },
	        py::arg("model"), py::arg("R1"), py::arg("R2"), py::arg("volume"), py::arg("gamma"), py::arg("theta") = 0.0,
	        py::arg("theta2") = py::none(), py::arg("rupture") = "willett", py::arg("linear_fmax") = 0.0, py::arg("linear_kc") = 0.0,
	        py::arg("calibrate_from") = "willett_full", py::arg("extrapolate") = false,
	        (std::string("Per-bridge invariants as a dict: R (effective radius) [m], theta [rad], rupture (gap) [m], force0 = F(0) [N], "
	                     "energy = integral of F over [0, rupture] [J], extrapolated (bool), and for linear_irreversible linear_fmax [N], linear_kc [N/m].")
	         + common_args())
	                .c_str());

	m.def(
	        "rupture_distance",
	        [](const std::string& rule, double R1, double R2, double volume, double theta, std::optional<double> theta2) {
		        return rupture_distance(rupture_from_name(rule), R1, R2, volume, theta, theta2.value_or(theta));
	        },
	        py::arg("rule"), py::arg("R1"), py::arg("R2"), py::arg("volume"), py::arg("theta") = 0.0, py::arg("theta2") = py::none(),
	        "Rupture distance [m] (largest surface gap) of a rule: lian, willett (Gladkyy2014 eq. 2), willett_elskamp (Elskamp2018 eq. "
	        "32). R1, R2 [m] (R2 = inf: wall), volume [m^3], theta, theta2 [rad]. Raises ValueError on bad input.");

	py::class_<yl::Bridge>(m, "YoungLaplaceBridge",
	                       "Exact pendular bridge of fixed volume (Young-Laplace, zero gravity) between spheres R1, R2 [m] "
	                       "(R2 = inf: sphere-plane), volume [m^3], contact angles theta1, theta2 [rad] (theta2 < 0: equal to "
	                       "theta1). The constructor follows the branch of solutions from contact to its fold, the true rupture "
	                       "gap. Raises ValueError for bad input and RuntimeError if no bridge exists.")
	        .def(py::init<double, double, double, double, double, double>(), py::arg("R1"), py::arg("R2"), py::arg("volume"),
	             py::arg("theta1") = 0.0, py::arg("theta2") = -1.0, py::arg("tolerance") = 1e-12)
	        .def_property_readonly("rupture_gap", &yl::Bridge::rupture_gap, "Largest gap with a stable bridge [m].")
	        .def(
	                "solve",
	                [](const yl::Bridge& b, double gap, double gamma) {
		                const yl::Solution s = b.solve(gap, gamma);
		                py::dict           d;
		                d["gap"] = s.gap, d["beta1"] = s.beta1, d["beta2"] = s.beta2, d["contact_radius1"] = s.contact_radius1;
		                d["contact_radius2"] = s.contact_radius2, d["neck_radius"] = s.neck_radius, d["pressure"] = s.pressure;
		                d["force_neck"] = s.force_neck, d["force_contact"] = s.force_contact, d["volume"] = s.volume;
		                d["volume1"] = s.volume1, d["volume2"] = s.volume2;
		                return d;
	                },
	                py::arg("gap"), py::arg("gamma"),
	                "Stable bridge at gap [m] in [0, rupture_gap], surface tension gamma [N/m]: dict with gap [m], beta1, beta2 "
	                "(filling angles) [rad], contact_radius1/2 [m], neck_radius [m], pressure (p_liquid - p_gas) [Pa], "
	                "force_neck and force_contact (attraction by the neck and contact-line methods) [N], volume [m^3], volume1 and "
	                "volume2 [m^3]: the liquid on solid 1's and solid 2's side of the neck (the narrowest section, where the "
	                "bridge breaks; at gap = rupture_gap, volume1/volume is the exact transfer ratio to solid 1).");

	m.def("table_axes", [] {
		py::dict d;
		py::list lnv, theta_s, rho, theta_l, tau;
		for (int i = 0; i < yltable::n_lnv; ++i) lnv.append(yltable::lnv_node(i));
		for (int j = 0; j < yltable::n_ts; ++j) theta_s.append(yltable::theta_s_node(j));
		for (double r : yltable::rho_nodes) rho.append(r);
		for (int m = 0; m < yltable::n_tl; ++m) theta_l.append(yltable::lobatto(m, yltable::n_tl));
		for (int i = 0; i < yltable::n_w; ++i) tau.append(yltable::tau_node(i));
		d["ln_vstar"] = lnv, d["rho"] = rho, d["theta_s"] = theta_s, d["theta_l_x"] = theta_l, d["tau"] = tau;
		d["theta_max"] = yltable::theta_max, d["theta_top"] = yltable::theta_top;
		return d;
	}, "Nodes of the young_laplace_table model: ln_vstar (V* = V/Rh^3), rho = R_small/R_large (0: plane), theta_s [rad] "
	   "(the contact angle on the smaller sphere, Chebyshev nodes on [0, theta_max]), theta_l_x (Chebyshev nodes x in [0, 1] "
	   "of s = cbrt(theta_l - c) from theta_l = 0 to theta_top, c the row's ridge in data/young_laplace_table_rows.csv), "
	   "tau = 1 - sqrt(1 - sqrt(1 - a/a_rupture)).");

	m.def("willett_coefficients", &willett_coefficients, py::arg("vstar"), py::arg("theta"),
	      "Willett's f1..f4 (Gladkyy2014 eq. B1-B4) for V* = V/R^3 [-] and theta [rad].");

	// ---- viscous bridge forces (Elskamp2018 eq. 25-29, 33); the YADE layer evaluates the same kernels ----
	m.def("viscous_laws", [] {
		py::list l;
		for (const auto& r : normal_viscous_laws()) l.append(py::make_tuple(r.name, r.reference));
		return l;
	}, "Normal viscous laws as (name, reference) tuples; the first (pitois) is the default.");

	m.def(
	        "viscous_normal_force",
	        [](const std::string& law, double S, double v_n, double R1, double R2, double eta, double volume, double S_min_factor) {
		        return normal_viscous_force(normal_viscous_from_name(law), S, v_n, R1, R2, eta, volume, S_min_factor);
	        },
	        py::arg("law"), py::arg("S"), py::arg("v_n"), py::arg("R1"), py::arg("R2"), py::arg("eta"), py::arg("volume") = 0.0,
	        py::arg("S_min_factor") = default_s_min_factor,
	        ("Normal viscous force [N] on particle 1 along n (n: unit vector from particle 1 to 2): f = -c v_n, so it "
	         "opposes the relative normal motion (f v_n <= 0; particle 2 gets -f).\n"
	         "    law: " + normal_viscous_names() + " (pitois: Elskamp2018 eq. 26, the default law; adams_perchard: eq. 25)\n"
	         "    S: surface separation [m]; evaluated at max(S, 0) + S_min, S_min = S_min_factor r* (added, Elskamp2018 "
	         "after eq. 29; an overlap S < 0 gets the force at contact)\n"
	         "    v_n: (v1 - v2) . n [m/s], > 0 approaching\n"
	         "    R1, R2: radii [m] (R2 = inf: wall); r* = R1 R2/(R1 + R2), the reduced radius (R1 for a wall)\n"
	         "    eta: dynamic viscosity [Pa s] >= 0 (0: exactly 0)\n"
	         "    volume: bridge volume [m^3], required by pitois, ignored by adams_perchard\n"
	         "    S_min_factor: S_min / r* [-], default 0.001\n"
	         "Raises ValueError naming the parameter, its value and its allowed range.").c_str());

	m.def(
	        "viscous_tangential",
	        [](double S, std::array<double, 3> n, std::array<double, 3> v_rel, double R1, double R2, double eta, std::array<double, 3> omega1,
	           std::array<double, 3> omega2, double S_min_factor) {
		        const TangentialViscous t = tangential_viscous(S, n, v_rel, omega1, omega2, R1, R2, eta, S_min_factor);
		        py::dict                d;
		        d["c_t"] = t.c_t, d["c_r"] = t.c_r, d["near"] = t.near;
		        d["force"] = t.force, d["moment1"] = t.moment1, d["moment2"] = t.moment2;
		        return d;
	        },
	        py::arg("S"), py::arg("n"), py::arg("v_rel"), py::arg("R1"), py::arg("R2"), py::arg("eta"),
	        py::arg("omega1") = std::array<double, 3> { 0, 0, 0 }, py::arg("omega2") = std::array<double, 3> { 0, 0, 0 },
	        py::arg("S_min_factor") = default_s_min_factor,
	        "Tangential viscous force and moments (Goldman et al.; Elskamp2018 eq. 28 for S_eff < 0.1 r*, eq. 29 beyond): "
	        "F1 = -c_t v_t - c_r (omega_r x n), v_t the tangential part of v_rel, omega_r = R1 omega1 + R2 omega2 [m/s]. "
	        "Returns a dict: c_t, c_r [N s/m], near (True: eq. 28), force [N] on particle 1 (particle 2: -force), "
	        "moment1 = R1 n x force and moment2 = R2 n x force [N m] (moment2 = 0 for a wall).\n"
	        "    S: surface separation [m] (floored as in viscous_normal_force)\n"
	        "    n: unit vector from particle 1 to particle 2; v_rel = v1 - v2 [m/s]; omega1, omega2 [rad/s] "
	        "(a wall: its velocity at the contact point in v_rel, omega2 = 0)\n"
	        "    R1, R2 [m] (R2 = inf: wall), eta [Pa s] >= 0, S_min_factor [-]\n"
	        "c_t is floored at 0 beyond S_eff = 6.03 r* (the printed form turns negative there); c_r jumps by 3.3 % at "
	        "S_eff = 0.1 r* (the paper's branches, kept). Raises ValueError naming the parameter and its allowed range.");

	// ---- transfer of a bridge's liquid at rupture (Elskamp2018 eq. 35-43, Richefeu2008) ----
	m.def(
	        "parabolic_transfer",
	        [](double R1, double R2, double volume, double S, double theta1, std::optional<double> theta2) {
		        const ParabolicBridge p = parabolic_transfer(R1, R2, volume, S, theta1, theta2.value_or(theta1));
		        py::dict              d;
		        d["a"] = p.a, d["b"] = p.b, d["c"] = p.c, d["d1"] = p.d1, d["d2"] = p.d2, d["length"] = p.length;
		        d["x_min"] = p.x_min, d["volume1"] = p.volume1, d["transfer1"] = p.transfer1;
		        return d;
	        },
	        py::arg("R1"), py::arg("R2"), py::arg("volume"), py::arg("S"), py::arg("theta1") = 0.0, py::arg("theta2") = py::none(),
	        "Elskamp2018's parabolic bridge at rupture (eq. 35-43, with the mirror of eq. 39 for solid 2): radii R1, R2 [m] "
	        "(R2 = inf: a plane, which needs theta2 >= 0.001 rad), volume [m^3], separation S [m] (the rupture distance), "
	        "contact angles [rad] (theta2 defaults to theta1). Returns a dict: the parabola a [1/m], b, c [m], cap heights d1, "
	        "d2 [m], length between the contact-line planes [m], x_min (narrowest section) [m], volume1 (left of it, to "
	        "solid 1) [m^3] and transfer1 = volume1/volume.");
	m.def("diameter_transfer", &diameter_transfer, py::arg("R1"), py::arg("R2"),
	      "Richefeu2008's transfer ratio R1/(R1 + R2) [-] (1 against a wall, R2 = inf).");

	m.def(
	        "exact_transfer",
	        [](double R1, double R2, double volume, double theta1, std::optional<double> theta2) { return exact_transfer(R1, R2, volume, theta1, theta2.value_or(theta1)); },
	        py::arg("R1"), py::arg("R2"), py::arg("volume"), py::arg("theta1") = 0.0, py::arg("theta2") = py::none(),
	      "The exact transfer ratio T1 [-]: the share of a bridge's liquid on solid 1's side of the neck at the exact rupture "
	      "(Young-Laplace solver), interpolated in young_laplace_table's data. R1, R2 [m] (R2 = inf: a plane), volume [m^3], "
	      "contact angles theta1 on solid 1 and theta2 on solid 2 [rad] (theta2 = None: equal). Raises ValueError outside the "
	      "table (V* = V/Rh^3 in [1e-5, 0.5], each angle <= 70 deg, R_small/R_large >= 1/4 or a plane).");
	m.def(
	        "transfer_ratio",
	        [](const std::string& rule, double R1, double R2, double volume, double S, double theta1, std::optional<double> theta2) {
		        return transfer_ratio(transfer_from_name(rule), R1, R2, volume, S, theta1, theta2.value_or(theta1));
	        },
	        py::arg("rule"), py::arg("R1"), py::arg("R2"), py::arg("volume"), py::arg("S"), py::arg("theta1") = 0.0, py::arg("theta2") = py::none(),
	        "T1 [-] of a transfer rule (PendularMat.transfer: exact, parabolic, diameter) for a bridge of volume [m^3] whose "
	        "rupture distance is S [m] (used by parabolic only).");
	m.def(
	        "transfer_rules",
	        [] {
		        py::list out;
		        for (const auto& t : transfer_rules()) out.append(py::make_tuple(t.name, t.source));
		        return out;
	        },
	        "The transfer rules as (name, source) pairs, in the order of PendularPhys.transferIndex.");
	m.def("film_contribution", &film_contribution, py::arg("Ri"), py::arg("Rj"), py::arg("film"),
	      "Shi & McCarthy (Elskamp2018 eq. 8; eq. 9 for Rj = inf, a wall): the liquid [m^3] a sphere of radius Ri [m] with the "
	      "film [m^3] gives to a new bridge with a solid of radius Rj [m].");
	m.def("wall_film_contribution", &wall_film_contribution, py::arg("Ri"), py::arg("W"),
	      "Elskamp2018 eq. (10): the liquid [m^3] a wall with the film thickness W [m] gives to a new bridge with a sphere of "
	      "radius Ri [m]: W pi/4 Ri^2.");
	m.def("film_thickness", &film_thickness, py::arg("R"), py::arg("film"),
	      "Elskamp2018 eq. (34): the thickness [m] of the film [m^3] on a sphere of radius R [m]: (3 film/(4 pi) + R^3)^(1/3) - R.");

	m.def("dynamic_rupture_distance", &dynamic_rupture_distance, py::arg("static"), py::arg("v_rel"), py::arg("eta"), py::arg("gamma"),
	      "Dynamic rupture distance [m] (Pitois et al., Elskamp2018 eq. 33): static * (1 + sqrt(|v_rel| eta / gamma)). "
	      "static: static rupture distance [m] > 0 (e.g. rupture_distance(...)); v_rel: relative speed |v1 - v2| [m/s] "
	      "(sign ignored); eta: viscosity [Pa s] >= 0 (0: the static distance); gamma: surface tension [N/m]. Raises "
	      "ValueError naming the parameter and its allowed range.");

	m.def("bond_cube", &bonds::cube, py::arg("R1"), py::arg("R2"),
	      "R^3 [m^3] of Richefeu2008 eq. (14), R = sqrt(R1 R2) (a wall, R2 = inf: the Derjaguin pair of radius 2 R1).");
	m.def(
	        "bond_threshold",
	        [](const std::string& rule, double R1, double R2, double gap, double theta1, std::optional<double> theta2) {
		        return bonds::threshold(rupture_from_name(rule), R1, R2, gap, theta1, theta2.value_or(theta1));
	        },
	        py::arg("rule"), py::arg("R1"), py::arg("R2"), py::arg("gap"), py::arg("theta1") = 0.0, py::arg("theta2") = py::none(),
	        "The least alpha [-] at which a pair at surface gap `gap` [m] is within the debonding distance of the rupture rule "
	        "(lian: Richefeu2008 eq. 6) for the bond volume V_b = alpha R^3 (eq. 14): 0 in contact, inf if no plausible volume reaches it.");
	m.def(
	        "share_liquid",
	        [](const std::vector<double>& threshold, const std::vector<double>& cube, double liquid) {
		        const bonds::Sharing s = bonds::share(threshold, cube, liquid);
		        return py::make_tuple(s.alpha, std::vector<bool>(s.bonded.begin(), s.bonded.end()));
	        },
	        py::arg("threshold"), py::arg("cube"), py::arg("liquid"),
	        "Richefeu2008 eq. (13)-(14) with the eligibility rule (iii): shares `liquid` [m^3] over candidate pairs given by their "
	        "bond_threshold and bond_cube; returns (alpha, bonded): V_b = alpha R^3 on each bonded pair, sum V_b = liquid, and the "
	        "bonds are the largest set, in order of threshold, whose every member is within its debonding distance.");
	m.def("kept_dry", &bonds::kept_dry, py::arg("id1"), py::arg("id2"), py::arg("fraction"), py::arg("seed"),
	      "Whether the pair (id1, id2) is kept dry for a dry fraction in [0, 1] and a seed (a hash of the unordered pair and the "
	      "seed: the same pairs at every call, in any order).");
}
