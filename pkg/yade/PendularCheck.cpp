// PendularCheck: what it does after the interaction loop of each step, and how it raises an error
// from inside a step.
#include "PendularCheck.hpp"
#include "Ip2_PendularMat_PendularMat_PendularPhys.hpp"
#include "Law2_ScGeom_PendularPhys_Bridge.hpp"
#include "PendularBonds.hpp"
#include "conventions.hpp"

#include <core/InteractionLoop.hpp>

#include <mpi.h>

#include <atomic>
#include <iostream>
#include <stdexcept>

namespace yade {

YADE_PLUGIN((PendularCheck));
CREATE_LOGGER(PendularCheck);

namespace {
	// Ranks of MPI_COMM_WORLD (1 without MPI, or before MPI_Init or after MPI_Finalize), and this rank.
	int mpiRanks(int* rank = nullptr)
	{
		int initialized = 0, finalized = 0, ranks = 1;
		MPI_Initialized(&initialized);
		MPI_Finalized(&finalized);
		if (initialized && !finalized) {
			MPI_Comm_size(MPI_COMM_WORLD, &ranks);
			if (rank) MPI_Comm_rank(MPI_COMM_WORLD, rank);
		}
		return ranks;
	}
	// PendularCheck.maxOverlap's range.
	bool validOverlapBound(Real maxOverlap) { return maxOverlap > 0 && maxOverlap <= 2; }
} // namespace

void PendularCheck::action()
{
	std::string message;
	bool        loopSeen = false;
	// A new bound (or a new engine after O.load): the step's reports were made with the old one.
	const bool fresh = !(alarmBound == maxOverlap) || alarmBodies != scene->bodies->size();
	bool newPair = false; // a pair of a new smallest critical time step
	static std::atomic<bool> unguardedWarned { false };
	if (!pendular::guardsInstalled() && !unguardedWarned.exchange(true))
		LOG_WARN("yade_capillary.patches.install() has not run in this process (yade_capillary.scene.engines() runs it): an error of PendularCheck "
		         "raised in O.run's thread may be missed by O.wait(), O.bodies.erase/clear and O.interactions.erase/clear do not account for the "
		         "liquid they remove, PendularIntegrator does not see later changes of its NewtonIntegrator's parameters, and PendularLoop keeps no records");
	for (const auto& engine : scene->engines) {
		if (engine.get() == this && !loopSeen)
			message = "PendularCheck must come after the interaction loop in O.engines (it settles the liquid of the step's bridges and raises "
			          "their input errors); yade_capillary.scene.engines places it there";
		const auto loop = YADE_PTR_DYN_CAST<InteractionLoop>(engine);
		if (!loop) continue;
		loopSeen = true;
		for (const auto& functor : loop->lawDispatcher->functors)
			if (const auto law = YADE_PTR_DYN_CAST<Law2_ScGeom_PendularPhys_Bridge>(functor)) {
				try {
					law->settleFilms(scene);
				} catch (const std::invalid_argument& e) {
					if (message.empty()) message = e.what();
				}
				if (!PendularBonds::of(scene)) {
					// The bonds broken in this step have no engine to place their liquid: it stays on their particles.
					const auto orphans = law->takeBondReturns();
					for (const auto& r : orphans)
						law->giveBack(scene, r.id, r.volume);
					if (!orphans.empty() && message.empty())
						message = "PendularMat.liquid = 'bonds' needs a PendularBonds engine after PendularCheck, which places the liquid of broken "
						          "bonds; the liquid of the bonds broken in this step stays on their particles (PendularState.film)";
				}
				law->zeroEmptyTotals();
				checkOverlaps(*law, fresh);
			}
		for (const auto& functor : loop->physDispatcher->functors) {
			const auto ip2 = YADE_PTR_DYN_CAST<Ip2_PendularMat_PendularMat_PendularPhys>(functor);
			if (!ip2) continue;
			const auto taken = ip2->takeCriticalDt();
			if (taken.dt < criticalDt) {
				criticalDt   = taken.dt;
				criticalPair = Vector2i(taken.id1, taken.id2);
				newPair      = true;
			}
			const std::string problem = ip2->takeError(scene);
			if (message.empty()) message = problem;
		}
	}
	if (fresh) {
		alarmBound  = maxOverlap;
		alarmBodies = scene->bodies->size();
	}
	// Checked after the films are settled, so that a bad value loses no liquid of this step.
	if (message.empty() && !validOverlapBound(maxOverlap))
		message = "PendularCheck.maxOverlap = " + capillary::format_value(maxOverlap) + "; allowed: (0, 2] (times the smaller radius of a pair)";
	if (message.empty() && !(dtSafety > 0 && dtSafety <= 1))
		message = "PendularCheck.dtSafety = " + capillary::format_value(dtSafety) + "; allowed: (0, 1] (times the critical time step)";
	if (message.empty()) message = checkDt(newPair);
	if (!message.empty()) raiseInStep(scene, message);
}

void PendularCheck::checkOverlaps(Law2_ScGeom_PendularPhys_Bridge& law, bool fresh)
{
	const auto report = law.takeOverlaps();
	if (fresh) {
		// The alarm is maxOverlap times the scene's smallest sphere radius: no contact above the
		// bound is below it. Bodies are scanned only when their number or the bound changes.
		Real smallest = std::numeric_limits<Real>::infinity();
		for (const auto& b : *scene->bodies)
			if (b)
				if (const auto* sphere = dynamic_cast<const Sphere*>(b->shape.get())) smallest = math::min(smallest, sphere->radius);
		law.overlapBound = maxOverlap;
		law.overlapAlarm = validOverlapBound(maxOverlap) ? maxOverlap * smallest : std::numeric_limits<Real>::infinity();
		return; // this step's reports used the old bound
	}
	if (report.count == 0) return;
	nOverlaps += report.count;
	largestOverlap = math::max(largestOverlap, report.largest);
	if (overlapWarned) return;
	overlapWarned = true;
	// A linear contact given by tc oscillates at omega = pi / tc (setContact); an undamped collision at
	// speed v0 peaks at the overlap v0 / omega = v0 tc / pi, so tc <= pi maxOverlap r / v0 keeps it below the bound.
	LOG_WARN("interaction " << report.id1 << "-" << report.id2 << ": overlap " << capillary::format_value(report.overlap) << " m = "
	                        << capillary::format_value(report.largest) << " times the smaller radius " << capillary::format_value(report.radius)
	                        << " m, above PendularCheck.maxOverlap = " << maxOverlap << " (impact speed about " << capillary::format_value(report.speed)
	                        << " m/s); with tc <= " << capillary::format_value(Mathr::PI * maxOverlap * report.radius / report.speed)
	                        << " s the overlap stays below the bound. Warned once; PendularCheck.nOverlaps counts them");
}

std::string PendularCheck::checkDt(bool newPair)
{
	if (!(scene->dt > dtSafety * criticalDt)) return "";
	const std::string pair = "interaction " + std::to_string(criticalPair[0]) + "-" + std::to_string(criticalPair[1]);
	if (adaptDt) {
		const int ranks = mpiRanks();
		if (ranks > 1) return "PendularCheck.adaptDt = True under MPI with " + std::to_string(ranks) + " ranks: each rank would change its own O.dt; set it False and O.dt from stable_dt()";
		const Real before = scene->dt;
		scene->dt         = dtSafety * criticalDt;
		++dtAdaptations;
		LOG_WARN("adaptDt: O.dt lowered from " << capillary::format_value(before) << " to " << capillary::format_value(scene->dt) << " s = dtSafety = "
		                                       << dtSafety << " times the critical time step of " << pair);
		return "";
	}
	if (scene->dt == warnedDt && !newPair) return ""; // once per value of O.dt, unless a new pair lowered the limit
	warnedDt = scene->dt;
	++dtWarnings;
	LOG_WARN("O.dt = " << capillary::format_value(scene->dt) << " s exceeds dtSafety = " << dtSafety << " times the smallest two-body critical time step "
	                   << capillary::format_value(criticalDt) << " s, of " << pair
	                   << ": contacts may gain energy or diverge; yade_capillary.scene.stable_dt() gives a stable time step, PendularCheck.adaptDt lowers O.dt by itself");
	return "";
}

void PendularCheck::raiseInStep(Scene* scene, const std::string& message)
{
	// Under mpiexec (yade.mpy), the other ranks wait for this one inside the step: an exception
	// here would leave them, and the master's O.run, blocked for ever. End the whole run instead,
	// with the message.
	int       rank  = 0;
	const int ranks = mpiRanks(&rank);
	if (ranks > 1) {
		LOG_ERROR("MPI rank " << rank << " of " << ranks << ": " << message << "; aborting all ranks (MPI_Abort)");
		std::cerr << "yade-capillary, MPI rank " << rank << ": ValueError: " << message << std::endl;
		MPI_Abort(MPI_COMM_WORLD, 1);
	}
	// O.step() runs the step in the Python thread, which holds the GIL and gets the exception
	// itself; YADE's simulation thread does not hold it, and its wait() may miss the error.
	pendular::rememberRaised(message, PyGILState_Check() ? nullptr : scene);
	throw std::invalid_argument(message);
}

} // namespace yade
