// PendularIntegrator (see PendularIntegrator.hpp): the parameters read from its NewtonIntegrator, the per-body pass by parts and the fallback to NewtonIntegrator.
#include "PendularIntegrator.hpp"
#include "Pendular.hpp"
#include "PendularLoop.hpp"

#include <core/Bound.hpp>
#include <pkg/dem/NewtonIntegrator.hpp>
#include <lib/pyutil/gil.hpp>

#include <chrono>
#include <cstring>
#include <set>

namespace yade {

YADE_PLUGIN((PendularIntegrator));
CREATE_LOGGER(PendularIntegrator);
std::atomic<long> PendularIntegrator::newtonVersion { 0 };

namespace {
	namespace py = boost::python;

	using pendular::prefetchObject;
	// Bodies ahead: the Body twice as far as its State and Bound, which are read from it.
	constexpr long prefetchAhead = 8;

	// NewtonIntegrator::cundallDamp2nd (Cundall's non-viscous damping of an acceleration).
	void cundallDamp2nd(Real damping, Real dt, const Vector3r& vel, Vector3r& accel)
	{
		for (int i = 0; i < 3; i++)
			accel[i] *= 1 - damping * math::sign(accel[i] * (vel[i] + 0.5 * dt * accel[i]));
	}
} // namespace

void PendularIntegrator::findNewton()
{
	if (!pendular::sameEngines(scannedEngines, scene->engines)) {
		newton.reset();
		loop.reset();
		cachedNewton = nullptr; // another list: its NewtonIntegrator's parameters are read again (see refresh)
		stiffnessTimeStepper = false;
		bool before          = true; // the NewtonIntegrator is the last one before this engine
		// Between the PendularLoop and this engine, engines that change no body's State or Bound object,
		// clump membership, flags or subdomain, nor the body container (the kinematic engines of our
		// scenes set velocities only): then the loop's gathering stands for this engine's check.
		static const std::set<std::string> harmless { "PendularCheck", "RotationEngine", "PendularRotationEngine", "TranslationEngine",
		                                              "NewtonIntegrator" };
		for (const auto& engine : scene->engines) {
			if (engine.get() == this) before = false;
			if (!engine) continue;
			// Matched by class name: only the members of the base Engine (dead, scene, action) are used in C++.
			const std::string name = engine->getClassName();
			if (before && name == "NewtonIntegrator") newton = engine;
			if (before) {
				if (dynamic_cast<const PendularLoop*>(engine.get())) loop = engine;
				else if (!harmless.count(name)) loop.reset();
			}
			stiffnessTimeStepper = stiffnessTimeStepper || name == "GlobalStiffnessTimeStepper";
		}
	}
	if (!newton)
		PendularCheck::raiseInStep(scene, "PendularIntegrator: no NewtonIntegrator before it in O.engines (it does that engine's step and "
		                                  "reads its parameters); yade_capillary.scene.engines places them. Under yade.mpy, which places its "
		                                  "engines next to NewtonIntegrator, use engines(integrator=\"newton\") or scene.newton_only(O.engines)");
	if (!newton->dead)
		PendularCheck::raiseInStep(scene, "PendularIntegrator: the NewtonIntegrator before it in O.engines has dead=False, so every body "
		                                  "would be moved twice per step; set its dead=True (yade_capillary.scene.engines does), or remove "
		                                  "the PendularIntegrator");
}

PendularIntegrator::Parameters PendularIntegrator::parameters() const
{
	Parameters p;
	gilLock    lock;
	try {
		const py::object py(newton);
		p.damping            = py::extract<Real>(py.attr("damping"));
		p.gravity            = py::extract<Vector3r>(py.attr("gravity"));
		p.dampGravity        = py::extract<bool>(py.attr("dampGravity"));
		p.exactAsphericalRot = py::extract<bool>(py.attr("exactAsphericalRot"));
		py::extract<long> mask(py.attr("mask"));
		p.mask = mask.check() ? int(mask()) : 1; // a mask that is not an int (YADE_MASK_ARBITRARY) is handed over
	} catch (const py::error_already_set&) {
		PyErr_Clear();
		PendularCheck::raiseInStep(scene, "PendularIntegrator: cannot read the parameters of the NewtonIntegrator before it");
	}
	return p;
}

std::string PendularIntegrator::unsupported(const Parameters& p, int threads, bool& fatal)
{
	fatal = false;
	if (scene->isPeriodic) return "periodic cell";
	if (scene->trackEnergy) return "energy tracking (O.trackEnergy)";
	if (stiffnessTimeStepper) return "density scaling (GlobalStiffnessTimeStepper)";
	if (p.mask > 0) return "NewtonIntegrator.mask";
	// Each body's State and Bound and the checks below: from the PendularLoop's gathering of this step
	// if nothing between them can have changed them (see findNewton), else read here (in a Gladkyy-size
	// cell a read of every Body is 5 % of a step).
	const auto& container = *scene->bodies;
	const long  n         = long(container.size());
	bodies                = nullptr;
	if (loop && !loop->dead) {
		const pendular::BodyPointers& gathered = static_cast<const PendularLoop&>(*loop).gatheredBodies();
		if (gathered.scene == scene && gathered.iter == scene->iter && long(gathered.states.size()) == n) bodies = &gathered;
	}
	fromLoop = bodies != nullptr;
	if (!bodies) {
		ownPointers.states.resize(n);
		ownPointers.bounds.resize(n);
		int clumps = 0, aspherical = 0, subdomains = 0;
#ifdef YADE_OPENMP
#pragma omp parallel for schedule(static) num_threads(threads) if (n >= parallelBodies) reduction(| : clumps, aspherical, subdomains)
#endif
		for (long id = 0; id < n; ++id) {
			if (id + prefetchAhead < n && container[id + prefetchAhead]) __builtin_prefetch(container[id + prefetchAhead].get());
			pendular::readBody(container[id].get(), scene->subdomain, ownPointers.states[id], ownPointers.bounds[id], clumps, aspherical, subdomains);
		}
		ownPointers.clumps     = clumps;
		ownPointers.aspherical = aspherical;
		ownPointers.subdomains = subdomains;
		bodies                 = &ownPointers;
	}
	if (bodies->subdomains) {
		fatal = true;
		return "PendularIntegrator: bodies of other subdomains (yade.mpy): its communication engines are placed next to the "
		       "NewtonIntegrator; build the engines with yade_capillary.scene.engines(integrator='newton')";
	}
	if (bodies->clumps) return "clumps";
	if (p.exactAsphericalRot && bodies->aspherical) return "aspherical bodies with NewtonIntegrator.exactAsphericalRot";
	return "";
}

// Where the installed YADE keeps NewtonIntegrator::maxVelocitySq: the headers' offset (YADE 2025.2; the
// members that Debian's 2023.02a lacks come after it), checked by setting the attribute through Python to
// two sentinels in turn; if the double there does not follow them, the only offset before it that does.
// The attribute's value is restored. Called with the GIL.
long PendularIntegrator::probeFlag() const
{
	py::object       py(newton);
	const Real       saved  = py::extract<Real>(py.attr("maxVelocitySq"));
	const char*      base   = reinterpret_cast<const char*>(newton.get());
	const long       header = long(reinterpret_cast<const char*>(&static_cast<const NewtonIntegrator*>(newton.get())->maxVelocitySq) - base);
	const Real       sentinels[2] = { 1.2345678901234567e-101, -7.654321098765432e+99 };
	std::vector<long> found;
	for (long offset = header; offset >= 0; offset -= long(sizeof(Real)))
		found.push_back(offset);
	for (const Real value : sentinels) {
		py.attr("maxVelocitySq") = value;
		std::vector<long> still;
		for (const long offset : found) {
			Real there;
			std::memcpy(&there, base + offset, sizeof(Real));
			if (there == value) still.push_back(offset);
		}
		found.swap(still);
	}
	py.attr("maxVelocitySq") = saved;
	return found.empty() ? -1 : found.front(); // the headers' offset first
}

void PendularIntegrator::refresh()
{
	gilLock lock;
	try {
		findNewton();
	} catch (const std::exception&) {
		return; // no NewtonIntegrator, or a live one: the step raises
	}
	cached        = parameters();
	cachedVersion = newtonVersion;
	if (cachedNewton != newton.get()) {
		cachedNewton = newton.get();
		try {
			flagOffset = probeFlag();
		} catch (const py::error_already_set&) {
			PyErr_Clear();
			flagOffset = -1;
		}
		if (flagOffset < 0) LOG_WARN("PendularIntegrator: NewtonIntegrator.maxVelocitySq not found in the object; it is set through Python at every step");
	}
}

void PendularIntegrator::action()
{
	findNewton();
	if (cachedNewton != newton.get() || cachedVersion != newtonVersion) refresh(); // takes the GIL
	const Parameters  p       = cached;
	const int         threads = pendular::passThreads(ompThreads);
	bool              fatal   = false;
	const std::string why     = unsupported(p, threads, fatal);
	if (fatal) PendularCheck::raiseInStep(scene, why);
	if (!why.empty()) {
		if (why != handedOverBecause) LOG_INFO("PendularIntegrator: the NewtonIntegrator does the step (" << why << ")");
		handedOverBecause = why;
		++nHandedOver;
		nIntegrated    = 0;
		newton->scene  = scene;
		newton->action();
		return;
	}
	const auto start = std::chrono::steady_clock::now();
	const Real flag = integrate(p, *bodies, threads);
	bodiesTime += Real(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
	if (flagOffset >= 0) {
		std::memcpy(reinterpret_cast<char*>(newton.get()) + flagOffset, &flag, sizeof(Real));
		return;
	}
	gilLock lock;
	try {
		py::object(newton).attr("maxVelocitySq") = flag;
	} catch (const py::error_already_set&) {
		PyErr_Clear();
		PendularCheck::raiseInStep(scene, "PendularIntegrator: cannot set NewtonIntegrator.maxVelocitySq (the collider's flag)");
	}
}

// NewtonIntegrator::action for a standalone body with spherical rotation in an aperiodic scene without
// energy tracking, density scaling or mask, in its order of operations (the same numbers bit for bit:
// tests/yade/test_integrator.py). Returns what NewtonIntegrator leaves in maxVelocitySq: the largest
// over the bodies with a bound of 0.5 (still within its sweep length) or 2 (beyond: the collider runs).
Real PendularIntegrator::integrate(const Parameters& p, const pendular::BodyPointers& bodies, int threads)
{
	const long          n      = long(bodies.states.size());
	State* const*       states = bodies.states.data();
	const Bound* const* bounds = bodies.bounds.data();
	const Real          dt     = scene->dt;
	ForceContainer& forces = scene->forces;
	forces.sync();
	// The container's summed entries themselves (what getForce and getTorque return once synced), without two
	// calls into libyade per body, which the compiler cannot inline (docs/performance.md, "Per-body checks
	// without two calls into libyade"). None if the container does not cover every body (getForce's zero
	// beyond its entries): then the calls.
	const pendular::SummedArrays summed = pendular::summedArrays(forces, n);
	Real flag  = 0;
	long count = 0;
	// Each thread the part of the bodies that it gathered in the PendularLoop of this step (bodies.parts).
#ifdef YADE_OPENMP
#pragma omp parallel num_threads(threads) if (n >= parallelBodies) reduction(max : flag) reduction(+ : count)
#endif
	{
	const auto part = pendular::partOf(bodies.parts, n, pendular::threadNumber(), pendular::teamSize());
	// The angular velocity whose rotation over dt was made last, and that rotation.
	Vector3r    rotated = Vector3r::Zero();
	Quaternionr rotation = Quaternionr::Identity();
	for (long id = part.first; id < part.second; ++id) {
		if (id + prefetchAhead < n && states[id + prefetchAhead]) {
			prefetchObject<1>(states[id + prefetchAhead]);
			if (bounds[id + prefetchAhead]) __builtin_prefetch(bounds[id + prefetchAhead]);
		}
		if (!states[id]) continue; // an erased body
		State& s = *states[id];
		const Vector3r f       = summed.forces ? summed.forces[id] : forces.getForce(Body::id_t(id));
		const Vector3r m       = summed.forces ? summed.torques[id] : forces.getTorque(Body::id_t(id));
		const unsigned blocked = s.blockedDOFs;
		if (blocked != State::DOF_ALL) {
			// NewtonIntegrator::computeAccel and computeAccelWithoutGravity + addGravity (dampGravity).
			Vector3r linAccel;
			if (blocked == 0) linAccel = p.dampGravity ? Vector3r(f / s.mass + p.gravity) : Vector3r(f / s.mass);
			else {
				linAccel = Vector3r::Zero();
				for (int i = 0; i < 3; i++)
					if (!(blocked & State::axisDOF(i, false))) linAccel[i] += p.dampGravity ? f[i] / s.mass + p.gravity[i] : f[i] / s.mass;
			}
			// With damping = 0, NewtonIntegrator's damping multiplies by exactly 1: skipped.
			if (s.isDamped && p.damping != 0) cundallDamp2nd(p.damping, dt, s.vel, linAccel);
			if (!p.dampGravity) {
				Vector3r g = p.gravity;
				if (blocked != 0) {
					g = Vector3r::Zero();
					for (int i = 0; i < 3; i++)
						if (!(blocked & State::axisDOF(i, false))) g[i] = p.gravity[i];
				}
				linAccel += g;
			}
			s.vel += dt * linAccel;
			// NewtonIntegrator::computeAngAccel
			Vector3r angAccel;
			if (blocked == 0) angAccel = m.cwiseQuotient(s.inertia);
			else {
				angAccel = Vector3r::Zero();
				for (int i = 0; i < 3; i++)
					if (!(blocked & State::axisDOF(i, true))) angAccel[i] += m[i] / s.inertia[i];
			}
			if (s.isDamped && p.damping != 0) cundallDamp2nd(p.damping, dt, s.angVel, angAccel);
			s.angVel += dt * angAccel;
		}
		// NewtonIntegrator::leapfrogTranslate and leapfrogSphericalRotate
		s.pos += s.vel * dt;
		const Real angle2 = s.angVel.squaredNorm();
		if (angle2 != 0) {
			// The rotation of this step, made again only for another angular velocity: the bodies of a
			// rotating wall (RotationEngine) share one, and a quaternion from an angle-axis is a sine, a
			// cosine and a square root (docs/performance.md, "The rotation of a step made once per angular
			// velocity"). The same inputs give the same quaternion: bit-identical to NewtonIntegrator.
			if (s.angVel != rotated) {
				const Real angle = math::sqrt(angle2);
				rotated          = s.angVel;
				rotation         = Quaternionr(AngleAxisr(angle * dt, s.angVel / angle));
			}
			s.ori = rotation * s.ori;
		}
		s.ori.normalize();
		++count;
		// NewtonIntegrator::saveMaximaDisplacement
		const Bound* bound = bounds[id];
		if (!bound) continue;
		const Vector3r disp    = s.pos - bound->refPos;
		const Real     maxDisp = math::max(math::abs(disp[0]), math::max(math::abs(disp[1]), math::abs(disp[2])));
		flag                   = math::max(flag, (!maxDisp || maxDisp < bound->sweepLength) ? Real(0.5) : Real(2));
	}
	}
	nIntegrated = count;
	return flag;
}

} // namespace yade
