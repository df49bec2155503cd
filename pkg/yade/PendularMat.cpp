// PendularMat: the checks of its attributes when they are assigned, and the names they hold resolved
// into the ids the Ip2 reads.
#include "PendularMat.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace yade {

YADE_PLUGIN((PendularMat));

namespace {
	using pendular::isSet;

	[[noreturn]] void badValue(const std::string& cls, const char* name, Real value, const char* range, const char* unit)
	{
		capillary::out_of_range(cls + "." + name, value, range, unit); // the kernels' one wording
	}
	// `rupture`: a static rule, optionally followed by +pitois (Pitois' dynamic rupture distance,
	// Elskamp2018 eq. 33); pitois alone is willett+pitois. Returns (static rule, dynamic).
	std::pair<capillary::Rupture, bool> parseRupture(const std::string& name)
	{
		static const std::string suffix = "+pitois";
		std::string              rule = name;
		bool                     dynamic = false;
		if (rule == "pitois") rule = "willett", dynamic = true;
		else if (rule.size() > suffix.size() && rule.compare(rule.size() - suffix.size(), suffix.size(), suffix) == 0) {
			rule.resize(rule.size() - suffix.size());
			dynamic = true;
		}
		for (const auto& r : capillary::rupture_rules())
			if (rule == r.name) return { r.rule, dynamic };
		throw std::invalid_argument("PendularMat.rupture = '" + name + "' is unknown; allowed: " + capillary::rupture_names()
		                            + ", each optionally followed by +pitois (the dynamic rupture distance, Elskamp2018 eq. 33), or pitois (= willett+pitois)");
	}
} // namespace

Real pendular::dampingRatioFor(Real en, bool approachOnly)
{
	const Real target = -math::log(en);
	// -ln en as a function of x, increasing (see the declaration).
	const auto loss = [approachOnly](Real x) { return approachOnly ? x * math::atan(1 / x) : x * (Mathr::PI - 2 * math::atan(x)); };
	Real       lo = 0, hi = 1e8;
	for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
		const Real x = (lo + hi) / 2;
		(loss(x) < target ? lo : hi) = x;
	}
	return (lo + hi) / 2;
}

void PendularMat::postLoad(PendularMat&)
{
	try {
		validate();
	} catch (const std::invalid_argument&) {
		restore(lastGood);
		throw;
	}
	lastGood = checked();
}

void PendularMat::validate()
{
	const std::string c = "PendularMat";
	if (isSet(tc) && !(tc > 0 && math::isfinite(tc))) badValue(c, "tc", tc, "(0, inf)", "s");
	if (normalDamping != "always" && normalDamping != "approach")
		throw std::invalid_argument(c + ".normalDamping = '" + normalDamping + "' is unknown; allowed: always, approach (Richefeu2008 eq. 3)");
	if (friction != "spring" && friction != "viscous")
		throw std::invalid_argument(c + ".friction = '" + friction + "' is unknown; allowed: spring, viscous (Richefeu2008 eq. 12)");
	const bool newApproach = normalDamping == "approach";
	if (isSet(en) && !(en > pendular::minRestitution(newApproach) && en <= 1))
		badValue(c, "en", en, newApproach ? "(exp(-1) = 0.3679, 1] with normalDamping='approach'" : "(exp(-2) = 0.1353, 1]", "-");
	if (isSet(et) && !(et > 0 && et <= 1)) badValue(c, "et", et, "(0, 1]", "-");
	if (isSet(kn) && !(kn > 0 && math::isfinite(kn))) badValue(c, "kn", kn, "(0, inf)", "N/m");
	if (isSet(cn) && !(cn >= 0 && math::isfinite(cn))) badValue(c, "cn", cn, "[0, inf)", "N s/m");
	if (isSet(ks) && !(ks >= 0 && math::isfinite(ks))) badValue(c, "ks", ks, "[0, inf)", "N/m");
	if (isSet(cs) && !(cs >= 0 && math::isfinite(cs))) badValue(c, "cs", cs, "[0, inf)", "N s/m");
	if (!(frictionAngle >= 0 && frictionAngle < Mathr::HALF_PI)) badValue(c, "frictionAngle", frictionAngle, "[0, pi/2)", "rad");
	if (!(rollingFriction >= 0 && math::isfinite(rollingFriction))) badValue(c, "rollingFriction", rollingFriction, "[0, inf)", "m");
	if (!(Vb >= 0 && math::isfinite(Vb))) badValue(c, "Vb", Vb, "[0, inf), and > 0 when wet", "m^3");
	if (!(gamma >= 0 && math::isfinite(gamma))) badValue(c, "gamma", gamma, "[0, inf), and > 0 when wet", "N/m");
	if (!(theta >= 0 && theta < Mathr::HALF_PI)) badValue(c, "theta", theta, "[0, pi/2) (radians)", "rad");
	if (!(linearFmax >= 0 && math::isfinite(linearFmax))) badValue(c, "linearFmax", linearFmax, "[0, inf)", "N");
	if (!(linearKc >= 0 && math::isfinite(linearKc))) badValue(c, "linearKc", linearKc, "[0, inf)", "N/m");
	if (!(eta >= 0 && eta <= capillary::viscous_limits::eta_max))
		badValue(c, "eta", eta, ("[0, " + capillary::format_value(capillary::viscous_limits::eta_max) + "]").c_str(), "Pa s");
	if (!(viscousSmin >= capillary::viscous_limits::s_min_factor_min && viscousSmin <= capillary::viscous_limits::s_min_factor_max))
		badValue(c, "viscousSmin", viscousSmin,
		         ("[" + capillary::format_value(capillary::viscous_limits::s_min_factor_min) + ", "
		          + capillary::format_value(capillary::viscous_limits::s_min_factor_max) + "]")
		                 .c_str(),
		         "-");
	// The names are resolved into locals: the members change only when every check has passed, so
	// that a rejected assignment leaves them as they were (restore() puts back the attributes only).
	const auto               parsed = parseRupture(rupture);
	capillary::Model         newModel, newCalibrate;
	capillary::NormalViscous newViscous;
	try {
		newModel     = capillary::model_from_name(model);
		newCalibrate = capillary::model_from_name(calibrateFrom);
	} catch (const std::invalid_argument& e) {
		throw std::invalid_argument(c + "." + e.what());
	}
	try {
		newViscous = capillary::normal_viscous_from_name(viscousNormal);
	} catch (const std::invalid_argument&) {
		throw std::invalid_argument(c + ".viscousNormal = '" + viscousNormal + "' is unknown; allowed: " + capillary::normal_viscous_names());
	}
	if (liquid != "fixed" && liquid != "film" && liquid != "bonds")
		throw std::invalid_argument(c + ".liquid = '" + liquid + "' is unknown; allowed: fixed, film, bonds");
	if (formation != "contact" && formation != "films")
		throw std::invalid_argument(c + ".formation = '" + formation + "' is unknown; allowed: contact, films (when the liquid films touch)");
	capillary::Transfer newTransfer;
	try {
		newTransfer = capillary::transfer_from_name(transfer);
	} catch (const std::invalid_argument& e) {
		throw std::invalid_argument(c + "." + e.what());
	}
	if (wet && parsed.second && !(eta > 0))
		throw std::invalid_argument(c + ".rupture = '" + rupture + "' (Pitois' dynamic rupture distance, Elskamp2018 eq. 33) needs eta > 0; eta = "
		                            + capillary::format_value(eta) + " Pa s (set eta before rupture, or use a static rule: "
		                            + capillary::rupture_names() + ")");
	if (newCalibrate == capillary::Model::linear_irreversible)
		throw std::invalid_argument(c + ".calibrateFrom = 'linear_irreversible' is not allowed; allowed: any other model");
	if (wet && !(Vb > 0)) badValue(c, "Vb", Vb, "(0, inf) when wet=True (set Vb before wet)", "m^3");
	if (wet && !(gamma > 0)) badValue(c, "gamma", gamma, "(0, inf) when wet=True (set gamma before wet)", "N/m");
	// The material alone decides the contact angle against the model's domain (and the
	// calibration model's): refused here rather than at the first interaction.
	if (wet && !extrapolate) {
		const bool calibrated = newModel == capillary::Model::linear_irreversible && !(linearFmax > 0 && linearKc > 0);
		for (const capillary::Model m : { newModel, calibrated ? newCalibrate : newModel }) {
			const capillary::ModelInfo& mi = capillary::info(m);
			if (!mi.domain.allows_theta(theta))
				badValue(c, "theta", theta, ("[0, " + capillary::format_value(mi.domain.theta_max) + "], the domain of model " + mi.name + " (" + mi.domain.source
				                             + "); set extrapolate=True to extrapolate").c_str(),
				         "rad");
		}
	}
	if (isSet(en)) dampingRatioN = pendular::dampingRatioFor(en, newApproach);
	approachDamping = newApproach;
	viscousFriction = friction == "viscous";
	modelId        = newModel;
	calibrateId    = newCalibrate;
	ruptureId      = parsed.first;
	dynamicRupture = parsed.second;
	viscousId      = newViscous;
	filmMode       = liquid == "film" || liquid == "bonds";
	bondsMode      = liquid == "bonds";
	filmFormation  = formation == "films";
	transferId     = newTransfer;
}

} // namespace yade
