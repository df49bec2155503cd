// PendularBonds: the engine of PendularMat.liquid = 'bonds' (Richefeu2008 section 2.4): shares the
// liquid of the scene over every pair within the debonding distance, and places the liquid of the
// bonds that break by one of the paper's protocols.
#pragma once

#include "YadeHeaders.hpp"
#include <core/GlobalEngine.hpp>

#include <vector>

namespace yade {

class Law2_ScGeom_PendularPhys_Bridge;
class PendularPhys;

class PendularBonds : public GlobalEngine {
public:
	// The protocols, selected once by index.
	enum Protocol { update, particles, lowest, neighbours };
	void action() override;
	// Shares all the liquid of the bonds-mode bodies of the current scene, with `added` [m^3] more, now
	// (between steps).
	void shareNow(Real added);
	void postLoad(PendularBonds&);
	// The engine of `scene` (nullptr if none) and whether the pair id1-id2 is kept dry by it.
	static PendularBonds* of(Scene* scene);
	bool                  keepsDry(Body::id_t id1, Body::id_t id2) const;
	// Whether a new contact of a pair takes the free liquid of its bodies.
	bool formsAtContact(Body::id_t id1, Body::id_t id2) const { return protocolIndex != update && !keepsDry(id1, id2); }
	DECLARE_LOGGER;

private:
	int  protocolIndex = update;
	bool flagsStale    = true; // protocol, dryFraction or seed changed: the pairs' flags are refreshed at the next step
	void share(Scene* scene, Law2_ScGeom_PendularPhys_Bridge& law, Real added);
	void place(Scene* scene, Law2_ScGeom_PendularPhys_Bridge& law, Body::id_t id, Real volume, Body::id_t partner);
	void refreshFlags(Scene* scene);

public:
	// clang-format off
	YADE_CLASS_BASE_DOC_ATTRS_CTOR_PY(PendularBonds, GlobalEngine,
		"The liquid shared over bonds of :yref:`PendularMat` ``liquid='bonds'`` (Richefeu2008 section 2.4). A sharing takes all the "
		"liquid of the bonds-mode bodies (their bonds and their free liquid, PendularState.film) and gives every pair within the "
		"debonding distance of its rupture rule a bond of volume V_b = alpha R^3, R = sqrt(R1 R2) (a wall counts as a sphere of 2 R1), "
		"alpha fixed by sum V_b = the liquid (eq. 13-14) together with the eligibility of each pair for its own V_b (rule iii; "
		"yade_capillary.kernels.share_liquid). The first step shares; then the protocol decides. update (protocol 1): a sharing at "
		"every run of the collider (InsertionSortCollider.numAction; or every ``interval`` steps); between them a broken bond's liquid waits on its two particles, "
		"in proportion to their diameters. particles (protocol 2, section 3.2): a broken bond's liquid goes to its two particles in "
		"proportion to their diameters (a wall gets none) and a new contact takes all the free liquid of both. lowest (protocol 3, "
		"section 4.2): each particle's share goes to its lowest bond (the contact point furthest along ``down``) in its lower "
		"hemisphere. neighbours (section 2.2): each particle's share goes to its remaining bonds in proportion to the partners' "
		"diameters (a wall as a sphere of twice the particle's radius). With lowest and neighbours a particle without such a bond "
		"keeps its share as free liquid, and a bond is filled at most to its largest volume (PendularPhys.VbMax), the rest staying "
		"free. Candidates are the pairs the collider lists (bounding boxes overlapping, InsertionSortCollider.verletDist): a bond "
		"longer than verletDist is an error. The liquid is conserved to rounding: Law2_ScGeom_PendularPhys_Bridge.liquidTotals. "
		"Place it after PendularCheck. One process (not under yade.mpy).",
		((std::string, protocol, "update", Attr::triggerPostLoad, "Where the liquid of a broken bond goes: update, particles, lowest or neighbours (see the class)."))
		((long, interval, 0, Attr::triggerPostLoad, "protocol='update': share every interval steps [-], >= 0; 0 (the default): at every run of the collider, the paper's update of the contact list."))
		((Real, dryFraction, 0, Attr::triggerPostLoad, "Fraction of the pairs kept without a bond [-], [0, 1] (Richefeu2008 Fig. 7: half the bonds); which pairs, by a hash of the pair and seed, so the same pairs stay dry at every sharing."))
		((long, seed, 0, Attr::triggerPostLoad, "Seed of the pairs kept dry [-], >= 0."))
		((Vector3r, down, Vector3r(0, 0, -1), Attr::triggerPostLoad, "protocol='lowest': the downward direction [-], non-zero (normalised when used)."))
		((Real, alpha, 0, Attr::readonly, "V_b / R^3 of the last sharing [-] (Richefeu2008 eq. 14); 0 before the first or without liquid."))
		((long, nShared, 0, Attr::readonly, "Bonds made by the last sharing [-]."))
		((long, nCandidates, 0, Attr::readonly, "Pairs that the last sharing considered [-] (the collider's pairs of two bonds-mode bodies, not kept dry)."))
		((long, nSharings, 0, Attr::readonly, "Sharings done [-]."))
		((long, lastSharing, -1, Attr::readonly, "Iteration of the last sharing [-] (-1: none)."))
		((Real, reach, 0, Attr::readonly, "The longest rupture distance of a bond of the last sharing [m]."))
		((long, colliderRuns, -1, Attr::readonly, "Runs of the scene's InsertionSortCollider (numAction) when this engine last looked [-] (protocol='update' shares when it changes)."))
		((long, nPlaced, 0, Attr::readonly, "Shares of broken bonds placed into other bonds (lowest, neighbours) [-]."))
		((long, nFree, 0, Attr::readonly, "Shares of broken bonds left as free liquid on a particle [-].")),
		/*ctor*/,
		.def("share", &PendularBonds::shareNow, (boost::python::arg("added") = 0.0),
		     "Share the liquid now (between steps): all the liquid of the bonds-mode bodies, plus added [m^3] (>= 0) of new liquid, "
		     "over the pairs within the debonding distance. yade_capillary.bonds.share_water gives the liquid of a water content.")
	);
	// clang-format on
};
REGISTER_SERIALIZABLE(PendularBonds);

} // namespace yade
