// PendularPhys: the physics of an interaction of two PendularMat bodies, with its liquid bridge.
#pragma once

#include "YadeHeaders.hpp"
#include "models.hpp"
#include "viscous.hpp"

#include <memory>
#include <string>

namespace yade {

class PendularPhys : public NormShearPhys {
public:
	capillary::Bridge bridge {}; // per-bridge invariants, rebuilt from the attributes by postLoad
	// Likewise for eta > 0 (null otherwise: an inviscid bridge carries a pointer, not the invariants).
	std::shared_ptr<const capillary::ViscousBridge> viscous;
	void              postLoad(PendularPhys&);
	void              buildBridge();
	// The viscous forces (eta > 0) of a bridge of this pair holding `volume` [m^3].
	std::shared_ptr<const capillary::ViscousBridge> viscousOf(Real volume) const;
	std::string       modelName() const;
	std::string       ruptureName() const;
	std::string       calibrateName() const;
	std::string       viscousName() const;
	std::string       transferName() const;
	bool              extrapolated() const { return bridge.extrapolated(); }
	virtual ~PendularPhys() = default;
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularPhys, NormShearPhys,
		"Interaction physics of :yref:`PendularMat`: contact parameters and one liquid bridge. State machine: no bridge -> "
		"formed at the first contact (``active``) -> broken beyond ``sCrit`` (the interaction is then removed, so a new bridge "
		"needs a new contact). ``normalForce`` includes the capillary force.",
		((Real, cn, 0, Attr::readonly, "Normal damping [N s/m]."))
		((Real, cs, 0, Attr::readonly, "Tangential damping [N s/m]; with viscousFriction the tangential viscosity gamma_t of Richefeu2008 eq. 12."))
		((Real, tangensOfFrictionAngle, 0, Attr::readonly, "Tangent of the contact friction angle [-]."))
		((Real, rollingFriction, 0, Attr::readonly, "Rolling friction mu_roll [m]: the moment mu_roll f_n against the relative rolling (PendularMat.rollingFriction, Elskamp2018 Table 3)."))
		((bool, approachDamping, false, Attr::readonly, "The normal dashpot acts only while approaching (PendularMat.normalDamping = 'approach', Richefeu2008 eq. 3)."))
		((bool, viscousFriction, false, Attr::readonly, "Viscous-regularised Coulomb friction without a tangential spring, cs the viscosity (PendularMat.friction = 'viscous', Richefeu2008 eq. 12)."))
		((bool, wet, false, Attr::readonly, "Both materials are wet: a bridge forms at contact."))
		((bool, active, false, Attr::readonly, "A liquid bridge exists (formed at contact, not yet broken)."))
		((bool, film, false, Attr::readonly, "The bridge's liquid comes from the bodies' films (PendularMat.liquid = 'film'); Vb is 0 until it forms."))
		((bool, bonds, false, Attr::readonly, "The bridge is a bond of PendularMat.liquid = 'bonds' (Richefeu2008 section 2.4): PendularBonds gives its volume and redistributes it when it breaks."))
		((bool, keptDry, false, Attr::readonly, "bonds: the pair is one of PendularBonds.dryFraction kept without a bond (Richefeu2008 Fig. 7)."))
		((bool, bondFormation, false, Attr::readonly, "bonds: a new contact takes the free liquid of both bodies (PendularBonds.protocol other than 'update', and not keptDry)."))
		((bool, filmFormation, false, Attr::readonly, "film: the bridge forms when the films touch (PendularMat.formation = 'films'), else at contact."))
		((bool, pending, false, Attr::readonly, "film: the bridge was asked for in this step; PendularCheck forms it at the end of the step."))
		((bool, forceInContact, false, Attr::readonly, "F(0) acts during overlap."))
		((Real, R1, 0, Attr::readonly, "Radius of the (first) sphere of the bridge [m]: body 1, or body 2 if body 1 is a wall or facet (swapped)."))
		((Real, R2, 0, Attr::readonly, "Radius of the other body [m] (inf for a wall or facet)."))
		((Real, Vb, 0, Attr::readonly, "Liquid bridge volume [m^3]."))
		((Real, gamma, 0, Attr::readonly, "Surface tension [N/m]."))
		((Real, theta1, 0, Attr::readonly, "Contact angle on body 1 [rad]."))
		((Real, theta2, 0, Attr::readonly, "Contact angle on body 2 [rad]."))
		((int, modelIndex, -1, Attr::readonly, "Index of the capillary model of this bridge in yade_capillary.kernels.MODEL_NAMES (resolved once, at creation; -1: no bridge); its name is ``model``."))
		((int, ruptureIndex, -1, Attr::readonly, "Index of the rupture rule in yade_capillary.kernels.RUPTURE_NAMES; its name is ``rupture``."))
		((int, calibrateIndex, -1, Attr::readonly, "linear_irreversible: index of the reference model of the calibration; its name is ``calibrateFrom``."))
		((bool, extrapolate, false, Attr::readonly, "The bridge may be outside its model's domain (PendularMat.extrapolate)."))
		((Real, linearFmax, 0, Attr::readonly, "linear_irreversible: maximum force as given [N] (0: calibrated)."))
		((Real, linearKc, 0, Attr::readonly, "linear_irreversible: stiffness as given [N/m] (0: calibrated)."))
		((Real, R, 0, Attr::readonly, "Effective radius 2R1R2/(R1+R2) [m]; 2R for a wall (Derjaguin sphere-plane limit)."))
		((Real, sCrit, 0, Attr::readonly, "Rupture distance: largest surface gap of the bridge [m]."))
		((Real, force0, 0, Attr::readonly, "Capillary force at contact F(0) [N]."))
		((Real, Fcap, 0, Attr::readonly, "Capillary force of the last step [N], positive = attraction."))
		((Real, eta, 0, Attr::readonly, "Liquid viscosity [Pa s] (0: no viscous force)."))
		((Real, viscousSmin, 0, Attr::readonly, "S_min / r* of the viscous forces [-]."))
		((int, viscousIndex, -1, Attr::readonly, "Index of the normal viscous law in yade_capillary.kernels.VISCOUS_NAMES (-1: no viscous force); its name is ``viscousNormal``."))
		((bool, dynamicRupture, false, Attr::readonly, "The rupture distance is stretched by Pitois' rule (Elskamp2018 eq. 33)."))
		((bool, swapped, false, Attr::readonly, "Body 1 is the wall or facet: R1 is the radius of body 2."))
		((Real, Fvisc, 0, Attr::readonly, "Normal viscous force of the last step [N], positive = attraction (separating); included in normalForce."))
		((Vector3r, viscousShear, Vector3r::Zero(), Attr::readonly, "Tangential viscous force on body 2 of the last step [N] (Elskamp2018 eq. 28, 29); not part of shearForce, which is the tangential spring."))
		((Real, sRupture, 0, Attr::readonly, "Rupture distance of the last step [m]: sCrit, stretched by the dynamic rule if dynamicRupture."))
		((int, transferIndex, -1, Attr::readonly, "film: index of the transfer rule in yade_capillary.kernels.TRANSFER_NAMES (-1: fixed volume); its name is ``transfer``."))
		((Real, transfer1, 0, Attr::readonly, "film: the share of Vb that goes back to the sphere of radius R1 at rupture [-] (the rest to the other body, or to the sphere too if that is a wall holding no film)."))
		((Real, VbMin, 0, Attr::readonly, "film: smallest bridge volume [m^3]: the smallest V* of the model's domain (and of the exact transfer table) times R^3."))
		((Real, VbMax, 0, Attr::readonly, "film: largest bridge volume [m^3]: Vb of the materials, and the largest V* of the model's domain (and of the exact transfer table) times R^3.")),
		createIndex();,
		.add_property("model", &PendularPhys::modelName, "Name of the capillary model of this bridge ('' without bridge).")
		.add_property("rupture", &PendularPhys::ruptureName, "Name of the rupture rule of this bridge.")
		.add_property("calibrateFrom", &PendularPhys::calibrateName, "linear_irreversible: name of the reference model of the calibration.")
		.add_property("extrapolated", &PendularPhys::extrapolated, "The bridge lies outside its model's domain and is extrapolated.")
		.add_property("viscousNormal", &PendularPhys::viscousName, "Name of the normal viscous law ('' without viscosity).")
		.add_property("transfer", &PendularPhys::transferName, "film: name of the transfer rule ('' for a fixed volume).")
	);
	// clang-format on
	REGISTER_CLASS_INDEX(PendularPhys, NormShearPhys);
};
REGISTER_SERIALIZABLE(PendularPhys);

namespace pendular {
	// The radius a bridge sees for a body [m]: a sphere's, capillary::wall_radius (inf) for a wall or facet.
	inline Real radiusOf(const shared_ptr<Body>& b)
	{
		const auto* sphere = dynamic_cast<const Sphere*>(b->shape.get());
		return sphere ? sphere->radius : capillary::wall_radius;
	}
} // namespace pendular

} // namespace yade
