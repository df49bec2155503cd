// PendularPhys: its bridge built from its attributes, and the names of its model, rules and laws.
#include "PendularPhys.hpp"
#include "transfer.hpp"

#include <string>

namespace yade {

YADE_PLUGIN((PendularPhys));

namespace {
	// The kernels' description of the pair's bridge.
	capillary::BridgeSpec specOf(const PendularPhys& p)
	{
		capillary::BridgeSpec s;
		s.R1             = p.R1;
		s.R2             = p.R2;
		s.volume         = p.Vb;
		s.gamma          = p.gamma;
		s.theta1         = p.theta1;
		s.theta2         = p.theta2;
		s.model          = capillary::Model(p.modelIndex);
		s.rupture        = capillary::Rupture(p.ruptureIndex);
		s.linear_fmax    = p.linearFmax;
		s.linear_kc      = p.linearKc;
		s.calibrate_from = capillary::Model(p.calibrateIndex);
		s.extrapolate    = p.extrapolate;
		// Every member of BridgeSpec is set above: this binding of all of them stops compiling when it gets another.
		[[maybe_unused]] const auto& [r1, r2, volume, gamma, theta1, theta2, model, rupture, fmax, kc, calibrate, extrapolate] = s;
		return s;
	}
} // namespace

std::string PendularPhys::modelName() const { return modelIndex < 0 ? "" : capillary::name_of(capillary::Model(modelIndex)); }
std::string PendularPhys::ruptureName() const
{
	return ruptureIndex < 0 ? "" : std::string(capillary::name_of(capillary::Rupture(ruptureIndex))) + (dynamicRupture ? "+pitois" : "");
}
std::string PendularPhys::viscousName() const { return viscousIndex < 0 ? "" : capillary::name_of(capillary::NormalViscous(viscousIndex)); }
std::string PendularPhys::transferName() const { return transferIndex < 0 ? "" : capillary::transfer_rules()[transferIndex].name; }
std::string PendularPhys::calibrateName() const { return calibrateIndex < 0 ? "" : capillary::name_of(capillary::Model(calibrateIndex)); }

void PendularPhys::buildBridge()
{
	const capillary::BridgeSpec spec = specOf(*this);
	bridge   = capillary::make_bridge(spec);
	R        = capillary::pair_of(spec).R;
	sCrit    = bridge.rupture;
	sRupture = bridge.rupture;
	force0   = bridge.force0;
	viscous.reset();
	if (eta > 0) viscous = viscousOf(Vb);
}

std::shared_ptr<const capillary::ViscousBridge> PendularPhys::viscousOf(Real volume) const
{
	return std::make_shared<const capillary::ViscousBridge>(
	        capillary::make_viscous(capillary::NormalViscous(viscousIndex), R1, R2, eta, volume, dynamicRupture ? gamma : 0, viscousSmin));
}

void PendularPhys::postLoad(PendularPhys&)
{
	// After O.load: the cached invariants are not serialized (a film-mode bridge has them once formed).
	if (wet && modelIndex >= 0 && (!film || active)) buildBridge();
	pending = false; // a request lives within one step; a saved one would block the pair's bridge for ever
}

} // namespace yade
