#include "Pendular.hpp"
#include "PendularLoop.hpp"

#include <core/InteractionLoop.hpp>

#include <mpi.h>

#include <boost/python/exception_translator.hpp>
#include <boost/python/raw_function.hpp>
#include <boost/weak_ptr.hpp>
#include <algorithm>
#include <atomic>
#include <unordered_map>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <typeinfo>

namespace yade {

YADE_PLUGIN((PendularState)(PendularMat)(PendularPhys)(Ip2_PendularMat_PendularMat_PendularPhys)(Law2_ScGeom_PendularPhys_Bridge)(PendularCheck));
CREATE_LOGGER(Ip2_PendularMat_PendularMat_PendularPhys);
CREATE_LOGGER(PendularCheck);

namespace {
	namespace py = boost::python;

	// O.run(n, True) and O.wait() rethrow an exception of the simulation thread as the
	// std::runtime_error that YADE's ThreadRunner made of it (its type is lost; O.step() keeps it
	// and Boost.Python turns std::invalid_argument into ValueError). This translator gives the
	// errors raised by PendularCheck back their ValueError; every other exception goes on to
	// Boost.Python's default translation.
	//
	// YADE's pyOmega::wait() (also the end of O.run(n, True)) returns at once, without looking at
	// ThreadRunner::workerThrew, when the simulation is no longer running at the moment it looks:
	// if the simulation thread raised and stopped before that moment, the error is silently lost.
	// This happens in O.run(n, True) when the Python thread loses the CPU between starting the
	// simulation thread and its first isRunning() check (under load, the erroneous first step is
	// over by then), and in O.run(); ...; O.wait() whenever the step fails before O.wait(). So an
	// error raised in the simulation thread is also kept here as undelivered, and Omega.run and
	// Omega.wait are wrapped (installGuards) to raise it when YADE's own wait() returned without it.
	struct Raised {
		std::string            message;             // of the last error raised by a PendularCheck
		bool                   undelivered = false; // raised in the simulation thread, not yet given to Python
		boost::weak_ptr<Scene> scene;               // where and at which step (a step that raises does not
		long                   iter = -1;           // complete: iter stays), to drop it once stale
	};
	std::mutex raisedMutex;
	Raised     raised;

	// `loop`: the scene of a step run by YADE's simulation thread, nullptr for O.step().
	void remember(const std::string& message, Scene* loop)
	{
		const std::lock_guard<std::mutex> lock(raisedMutex);
		raised.message     = message;
		raised.undelivered = loop != nullptr;
		raised.scene.reset();
		if (!loop) return;
		const auto& current = Omega::instance().getScene();
		if (current.get() == loop) raised.scene = current;
		raised.iter = loop->iter;
	}
	void translateRaised(const std::runtime_error& e)
	{
		bool ours;
		{
			const std::lock_guard<std::mutex> lock(raisedMutex);
			ours = typeid(e) == typeid(std::runtime_error) && !raised.message.empty() && raised.message == e.what();
			if (ours) raised.undelivered = false; // YADE's wait() found it
		}
		if (!ours) throw;
		PyErr_SetString(PyExc_ValueError, e.what());
	}
	const bool translatorRegistered = (boost::python::register_exception_translator<std::runtime_error>(&translateRaised), true);

	// After YADE's wait() returned normally: raise the error that stopped the simulation thread if
	// wait() missed it, as the ValueError O.step() gives. An error of an earlier run, or of a scene
	// that has been replaced or stepped on since, is dropped (YADE forgets its workerThrew likewise).
	void deliverMissed()
	{
		std::string message;
		{
			const std::lock_guard<std::mutex> lock(raisedMutex);
			if (!raised.undelivered || Omega::instance().isRunning()) return;
			raised.undelivered  = false;
			const auto& current = Omega::instance().getScene();
			if (!current || raised.scene.lock() != current || current->iter != raised.iter) return;
			message = raised.message;
		}
		throw std::invalid_argument(message);
	}
	// Omega.run and Omega.wait of yade.wrapper before installGuards wrapped them (never freed: they
	// must not be released after the interpreter is finalized).
	py::object*       yadeRun  = nullptr;
	py::object*       yadeWait = nullptr;
	std::atomic<bool> guarded { false }; // installGuards has run (read by the simulation thread)

	py::object guardedRun(py::tuple args, py::dict kw) // Omega.run(self, nSteps=-1, wait=False)
	{
		if (!Omega::instance().isRunning()) {
			const std::lock_guard<std::mutex> lock(raisedMutex);
			raised.undelivered = false; // a new run starts: an undelivered error of the last one is stale
		}
		py::object       result = (*yadeRun)(*args, **kw);
		const py::object wait   = py::len(args) > 2 ? py::object(args[2]) : kw.get("wait", false);
		if (PyObject_IsTrue(wait.ptr()) == 1) deliverMissed();
		return result;
	}
	// Python paths that remove bodies or interactions: the liquid they hold is accounted for first by
	// every law of the current scene (Law2_ScGeom_PendularPhys_Bridge::eraseBody, releasePair,
	// clearBodies), then YADE's own method runs.
	template <class F> void forEachLaw(const F& f)
	{
		const auto& scene = Omega::instance().getScene();
		if (!scene) return;
		for (const auto& engine : scene->engines)
			if (const auto loop = YADE_PTR_DYN_CAST<InteractionLoop>(engine))
				for (const auto& functor : loop->lawDispatcher->functors)
					if (const auto law = YADE_PTR_DYN_CAST<Law2_ScGeom_PendularPhys_Bridge>(functor)) f(*law, scene.get());
	}
	py::object *yadeErase = nullptr, *yadeClear = nullptr, *yadeIntrErase = nullptr, *yadeIntrClear = nullptr;
	py::object  guardedErase(py::tuple args, py::dict kw) // BodyContainer.erase(self, id, eraseClumpMembers=False)
	{
		PendularLoop::syncCurrent(true); // the liquid accounts read the objects, which then change
		py::extract<int> id(py::len(args) > 1 ? py::object(args[1]) : kw.get("id"));
		const py::object members = py::len(args) > 2 ? py::object(args[2]) : kw.get("eraseClumpMembers", false);
		if (id.check()) forEachLaw([&](Law2_ScGeom_PendularPhys_Bridge& law, Scene* scene) { law.eraseBody(scene, id(), PyObject_IsTrue(members.ptr()) == 1); });
		return (*yadeErase)(*args, **kw);
	}
	py::object guardedClear(py::tuple args, py::dict kw)
	{
		PendularLoop::syncCurrent(true); // the liquid accounts read the objects, which then change
		forEachLaw([](Law2_ScGeom_PendularPhys_Bridge& law, Scene* scene) { law.clearBodies(scene); });
		return (*yadeClear)(*args, **kw);
	}
	py::object guardedIntrErase(py::tuple args, py::dict kw) // InteractionContainer.erase(self, id1, id2)
	{
		PendularLoop::syncCurrent(true); // the liquid accounts read the objects, which then change
		if (py::len(args) > 2) {
			py::extract<int> id1(args[1]), id2(args[2]);
			if (id1.check() && id2.check())
				forEachLaw([&](Law2_ScGeom_PendularPhys_Bridge& law, Scene* scene) {
					if (!scene->bodies->exists(id1()) || !scene->bodies->exists(id2())) return;
					if (const auto& I = scene->interactions->find(id1(), id2())) law.releasePair(scene, *I);
				});
		}
		return (*yadeIntrErase)(*args, **kw);
	}
	py::object guardedIntrClear(py::tuple args, py::dict kw)
	{
		PendularLoop::syncCurrent(true); // the liquid accounts read the objects, which then change
		forEachLaw([](Law2_ScGeom_PendularPhys_Bridge& law, Scene* scene) {
			for (const auto& I : *scene->interactions) law.releasePair(scene, *I);
		});
		return (*yadeIntrClear)(*args, **kw);
	}
	py::object guardedWait(py::tuple args, py::dict kw)
	{
		py::object result = (*yadeWait)(*args, **kw);
		deliverMissed();
		return result;
	}


	// Stability limit of YADE's leapfrog (NewtonIntegrator: v(t+dt/2) = v(t-dt/2) + dt F(t)/m,
	// x(t+dt) = x(t) + dt v(t+dt/2)) for m x'' + c x' + k x = 0 with the damping force taken from
	// v(t-dt/2), as the Law2 does. With h = w0 dt, w0^2 = k/m, d = c dt/m, the step matrix of
	// (x, v) has trace 2 - h^2 - d and determinant 1 - d; Jury's conditions |1 - d| < 1 and
	// 1 + trace + det > 0 give h^2 + 2d < 4, i.e. dt < (2/w0)(sqrt(1 + z^2) - z) with
	// z = c/(2 sqrt(k m)): 2/w0 undamped, smaller with damping. It is the central-difference limit
	// with damping of Belytschko, Liu & Moran (2000), Nonlinear Finite Elements for Continua and
	// Structures, chapter 6. A damper alone (k = 0) is the limit 2 m/c; inf for no stiffness and no damping, or an immovable mass.
	Real oscillatorLimit(Real k, Real c, Real m)
	{
		if (!(m > 0) || !math::isfinite(m)) return std::numeric_limits<Real>::infinity();
		if (!(k > 0)) return c > 0 ? 2 * m / c : std::numeric_limits<Real>::infinity(); // the limit k -> 0: a damper alone
		const Real w0 = math::sqrt(k / m), z = c / (2 * math::sqrt(k * m));
		return 2 / w0 * (math::sqrt(1 + z * z) - z);
	}
	bool heavy(const Body& b) { return !b.isDynamic() || !(b.state->mass > 0); }
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
	// Mass of the tangential motion of the contact point: 1/m_t = sum over the dynamic bodies of
	// 1/m + r^2/I (sliding plus rolling; r the sphere radius, I the smallest principal inertia);
	// 2/7 m for a solid sphere against a wall.
	Real tangentialMass(const Body& b1, const Body& b2)
	{
		Real inverse = 0;
		for (const Body* b : { &b1, &b2 }) {
			if (heavy(*b)) continue;
			inverse += 1 / b->state->mass;
			const auto* sphere = dynamic_cast<const Sphere*>(b->shape.get());
			const Real  inertia = b->state->inertia.minCoeff();
			if (sphere && inertia > 0) inverse += sphere->radius * sphere->radius / inertia;
		}
		return inverse > 0 ? 1 / inverse : std::numeric_limits<Real>::infinity();
	}
	// Effective mass of the normal motion: a body that does not move under forces acts as an
	// infinitely heavy partner (if neither moves, the contact parameters still need a mass).
	Real effectiveMass(const Body& b1, const Body& b2)
	{
		const Real mass1 = b1.state->mass, mass2 = b2.state->mass;
		const bool heavy1 = heavy(b1), heavy2 = heavy(b2);
		if (heavy1 && !heavy2) return mass2;
		if (heavy2 && !heavy1) return mass1;
		return (mass1 > 0 && mass2 > 0) ? mass1 * mass2 / (mass1 + mass2) : math::max(mass1, mass2);
	}
	// The viscous forces of a bridge (eta > 0) are dashpots in parallel with the contact's; their
	// coefficients are largest at contact (S_eff = S_min), which bounds the separated bridge too.
	// A film-mode pair has no bridge yet when its interaction is made (its volume is known only when
	// it forms): its limit is that of the largest bridge it can form, VbMax. That bounds every
	// volume: Pitois' coefficient grows with V (Elskamp2018 eq. 26), Adams-Perchard's and Goldman's
	// do not depend on it (eq. 25, 28, 29).
	Real pairCriticalDt(const PendularPhys& p, const Body& b1, const Body& b2)
	{
		if (heavy(b1) && heavy(b2)) return std::numeric_limits<Real>::infinity();
		Real cn = p.cn, cs = p.cs;
		std::shared_ptr<const capillary::ViscousBridge> viscous = p.viscous;
		if (!viscous && p.wet && p.film && p.eta > 0)
			viscous = p.viscousOf(p.VbMax);
		if (viscous) {
			double ct, cr;
			bool near;
			viscous->tangential_coefficients(0, ct, cr, near);
			cn += viscous->normal_coefficient(0);
			cs += ct + cr;
		}
		return math::min(oscillatorLimit(p.kn, cn, effectiveMass(b1, b2)), oscillatorLimit(p.ks, cs, tangentialMass(b1, b2)));
	}

} // namespace

void PendularCheck::action()
{
	std::string message;
	bool        loopSeen = false;
	// A new bound (or a new engine after O.load): the step's reports were made with the old one.
	const bool fresh = !(alarmBound == maxOverlap) || alarmBodies != scene->bodies->size();
	bool newPair = false; // a pair of a new smallest critical time step
	static std::atomic<bool> unguardedWarned { false };
	if (!guarded && !unguardedWarned.exchange(true))
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
	remember(message, PyGILState_Check() ? nullptr : scene);
	throw std::invalid_argument(message);
}

void PendularCheck::installGuards()
{
	if (yadeRun) return;
	py::object wrapper = py::import("yade.wrapper"), omega = wrapper.attr("Omega");
	yadeRun          = new py::object(omega.attr("run"));
	yadeWait         = new py::object(omega.attr("wait"));
	py::object run = py::raw_function(guardedRun, 1), wait = py::raw_function(guardedWait, 1);
	run.attr("__doc__")  = yadeRun->attr("__doc__");
	wait.attr("__doc__") = yadeWait->attr("__doc__");
	// Plain attribute assignment (Boost.Python's add_to_namespace would add an overload instead).
	omega.attr("run")  = run;
	omega.attr("wait") = wait;
	// The same for the Python paths that remove bodies or interactions (their liquid is accounted for).
	const auto wrap = [](py::object cls, const char* name, py::object*& original, py::object (*guarded)(py::tuple, py::dict), const char* note) {
		original       = new py::object(cls.attr(name));
		py::object fun = py::raw_function(guarded, 1);
		fun.attr("__doc__") = std::string(py::extract<std::string>(original->attr("__doc__"))) + "\n(yade-capillary: " + note + ")";
		cls.attr(name)      = fun;
	};
	const char* note = "the liquid of the bridges and films removed is accounted for, see Law2_ScGeom_PendularPhys_Bridge.liquidTotals";
	wrap(wrapper.attr("BodyContainer"), "erase", yadeErase, guardedErase, note);
	wrap(wrapper.attr("BodyContainer"), "clear", yadeClear, guardedClear, note);
	wrap(wrapper.attr("InteractionContainer"), "erase", yadeIntrErase, guardedIntrErase, note);
	wrap(wrapper.attr("InteractionContainer"), "clear", yadeIntrClear, guardedIntrClear, note);
	guarded = true;
}

namespace {

	[[noreturn]] void badValue(const std::string& cls, const char* name, Real value, const char* range, const char* unit)
	{
		capillary::out_of_range(cls + "." + name, value, range, unit); // the kernels' one wording
	}
	bool isSet(Real x) { return !math::isnan(x); }

	// Schwager & Poeschel 2007: a linear spring-dashpot contact that is not allowed to attract
	// ends when the force reaches zero, before the overlap does; its restitution coefficient is
	// en = exp(-x (pi - 2 atan x)) with x = beta/omega (damping rate over damped frequency), not
	// the textbook exp(-pi x). Returns x for a given en in (exp(-2), 1] (the function is
	// increasing in x and tends to 2 as x -> infinity).
	Real dampingRatioFor(Real en)
	{
		const Real target = -math::log(en);
		Real       lo = 0, hi = 1e8;
		for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
			const Real x = (lo + hi) / 2;
			(x * (Mathr::PI - 2 * math::atan(x)) < target ? lo : hi) = x;
		}
		return (lo + hi) / 2;
	}
	const Real minEn = math::exp(Real(-2));

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
		return s;
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

	Real radiusOf(const shared_ptr<Body>& b)
	{
		const auto* sphere = dynamic_cast<const Sphere*>(b->shape.get());
		return sphere ? sphere->radius : capillary::wall_radius;
	}
} // namespace

PendularMat::Checked PendularMat::checked() const
{
	return { tc,    en,         et,       kn,  cn,          ks,  cs,             frictionAngle, Vb,    gamma,   theta,
		 linearFmax, linearKc, eta, viscousSmin, wet, forceInContact, extrapolate,   model, rupture, calibrateFrom, viscousNormal, liquid, formation, transfer };
}

void PendularMat::restore(const Checked& c)
{
	std::tie(tc, en, et, kn, cn, ks, cs, frictionAngle, Vb, gamma, theta, linearFmax, linearKc, eta, viscousSmin)
	        = std::tie(c.tc, c.en, c.et, c.kn, c.cn, c.ks, c.cs, c.frictionAngle, c.Vb, c.gamma, c.theta, c.linearFmax, c.linearKc, c.eta, c.viscousSmin);
	std::tie(wet, forceInContact, extrapolate, model, rupture, calibrateFrom, viscousNormal, liquid, formation, transfer)
	        = std::tie(c.wet, c.forceInContact, c.extrapolate, c.model, c.rupture, c.calibrateFrom, c.viscousNormal, c.liquid, c.formation, c.transfer);
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
	if (isSet(en) && !(en > minEn && en <= 1)) badValue(c, "en", en, "(exp(-2) = 0.1353, 1]", "-");
	if (isSet(et) && !(et > 0 && et <= 1)) badValue(c, "et", et, "(0, 1]", "-");
	if (isSet(kn) && !(kn > 0 && math::isfinite(kn))) badValue(c, "kn", kn, "(0, inf)", "N/m");
	if (isSet(cn) && !(cn >= 0 && math::isfinite(cn))) badValue(c, "cn", cn, "[0, inf)", "N s/m");
	if (isSet(ks) && !(ks >= 0 && math::isfinite(ks))) badValue(c, "ks", ks, "[0, inf)", "N/m");
	if (isSet(cs) && !(cs >= 0 && math::isfinite(cs))) badValue(c, "cs", cs, "[0, inf)", "N s/m");
	if (!(frictionAngle >= 0 && frictionAngle < Mathr::HALF_PI)) badValue(c, "frictionAngle", frictionAngle, "[0, pi/2)", "rad");
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
	if (liquid != "fixed" && liquid != "film") throw std::invalid_argument(c + ".liquid = '" + liquid + "' is unknown; allowed: fixed, film");
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
	if (isSet(en)) dampingRatioN = dampingRatioFor(en);
	modelId        = newModel;
	calibrateId    = newCalibrate;
	ruptureId      = parsed.first;
	dynamicRupture = parsed.second;
	viscousId      = newViscous;
	filmMode       = liquid == "film";
	filmFormation  = formation == "films";
	transferId     = newTransfer;
}

void PendularState::postLoad(PendularState&)
{
	const auto refuseRange = [this](const char* name, Real value, const std::string& range, const char* unit) {
		film     = lastFilm;
		filmArea = lastFilmArea;
		capillary::out_of_range(std::string("PendularState.") + name, value, range, unit);
	};
	// Plausible: at most the volume of a body of the largest plausible radius (1 km), and a wettable
	// area of at least a square nanometre, so that the film thickness film/filmArea stays finite.
	const Real rmin = capillary::Plausible::radius_min, rmax = capillary::Plausible::radius_max;
	if (!(film >= 0 && film <= rmax * rmax * rmax)) refuseRange("film", film, "[0, " + capillary::format_value(rmax * rmax * rmax) + "]", "m^3");
	if (!(filmArea == 0 || (filmArea >= rmin * rmin && filmArea <= rmax * rmax)))
		refuseRange("filmArea", filmArea, "0 (holds no film) or [" + capillary::format_value(rmin * rmin) + ", " + capillary::format_value(rmax * rmax) + "]", "m^2");
	lastFilm     = film;
	lastFilmArea = filmArea;
}

Real PendularState::thickness(Real R) const
{
	if (!math::isinf(R)) return capillary::film_thickness(R, film);
	return filmArea > 0 ? film / filmArea : 0;
}

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

void Ip2_PendularMat_PendularMat_PendularPhys::go(const shared_ptr<Material>& b1, const shared_ptr<Material>& b2, const shared_ptr<Interaction>& I)
{
	if (I->phys) return;
	const auto& m1    = static_cast<const PendularMat&>(*b1);
	const auto& m2    = static_cast<const PendularMat&>(*b2);
	const auto& body1 = Body::byId(I->getId1(), scene);
	const auto& body2 = Body::byId(I->getId2(), scene);
	auto        phys  = shared_ptr<PendularPhys>(new PendularPhys());
	I->phys           = phys;
	// No exception may leave InteractionLoop's OpenMP loop: errors are recorded for PendularCheck.
	try {
		setContact(phys, m1, m2, body1, body2);
	} catch (const std::exception& e) {
		// kn stays 0: the Law2 resets the interaction, so this error comes again at the next step
		// instead of leaving a pair that passes through without a contact force.
		report(e.what(), *I);
		return;
	}
	try {
		setLiquid(phys, m1, m2, body1, body2);
	} catch (const std::exception& e) {
		phys->wet    = false; // the bridge is refused, the contact law stays
		phys->viscous.reset();
		report(e.what(), *I);
	}
	const Real                        dt = pairCriticalDt(*phys, *body1, *body2);
	const std::lock_guard<std::mutex> lock(dtMutex);
	if (dt < newCriticalDt.dt) newCriticalDt = { dt, I->getId1(), I->getId2() };
}

void Ip2_PendularMat_PendularMat_PendularPhys::report(const std::string& what, const Interaction& I)
{
	const std::string                 message = what + " (interaction " + std::to_string(I.getId1()) + "-" + std::to_string(I.getId2()) + ")";
	const std::lock_guard<std::mutex> lock(errorMutex);
	if (errorPending && errorScene == scene && errorIter == scene->iter) return; // the first error of the step is raised
	errorPending     = true;
	error            = message;
	errorScene       = scene;
	errorIter        = scene->iter;
	// Without PendularCheck the run stops after this step; PendularCheck raises instead and puts
	// stopAtIter back, so that a user who catches the error can go on running.
	stopAtIterBefore  = scene->stopAtIter;
	scene->stopAtIter = scene->iter + 1;
	LOG_ERROR(message);
}

std::string Ip2_PendularMat_PendularMat_PendularPhys::takeError(Scene* current)
{
	const std::lock_guard<std::mutex> lock(errorMutex);
	if (!errorPending) return "";
	errorPending = false;
	if (errorScene != current || errorIter != current->iter) return ""; // left by a step without PendularCheck
	current->stopAtIter = stopAtIterBefore;
	return error;
}

Ip2_PendularMat_PendularMat_PendularPhys::PairDt Ip2_PendularMat_PendularMat_PendularPhys::takeCriticalDt()
{
	const std::lock_guard<std::mutex> lock(dtMutex);
	const PairDt                      taken = newCriticalDt;
	newCriticalDt                           = { std::numeric_limits<Real>::infinity(), -1, -1 };
	return taken;
}

Real Ip2_PendularMat_PendularMat_PendularPhys::criticalDt(Body::id_t id1, Body::id_t id2)
{
	scene              = Omega::instance().getScene().get(); // called from Python, outside any loop
	const auto& bodies = scene->bodies;
	if (!bodies->exists(id1) || !bodies->exists(id2) || id1 == id2)
		throw std::invalid_argument("criticalDt: need two different existing bodies, got ids " + std::to_string(id1) + " and " + std::to_string(id2));
	const auto& body1 = (*bodies)[id1];
	const auto& body2 = (*bodies)[id2];
	const auto* m1    = dynamic_cast<const PendularMat*>(body1->material.get());
	const auto* m2    = dynamic_cast<const PendularMat*>(body2->material.get());
	if (!m1 || !m2)
		throw std::invalid_argument("criticalDt: bodies " + std::to_string(id1) + " and " + std::to_string(id2) + " must both have a PendularMat");
	auto phys = shared_ptr<PendularPhys>(new PendularPhys());
	setContact(phys, *m1, *m2, body1, body2);
	try {
		setLiquid(phys, *m1, *m2, body1, body2);
	} catch (const std::exception&) { // a refused bridge: the pair has the contact law alone, as in go()
		phys->viscous.reset();
	}
	return pairCriticalDt(*phys, *body1, *body2);
}

void Ip2_PendularMat_PendularMat_PendularPhys::setContact(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	const Real massR = effectiveMass(*body1, *body2);
	const bool byTime = isSet(m1.tc) && isSet(m1.en) && isSet(m1.et) && isSet(m2.tc) && isSet(m2.en) && isSet(m2.et);
	const bool byStiff = isSet(m1.kn) && isSet(m1.cn) && isSet(m1.ks) && isSet(m1.cs) && isSet(m2.kn) && isSet(m2.cn) && isSet(m2.ks)
	        && isSet(m2.cs);
	if (byTime == byStiff) {
		auto given = [](const PendularMat& m) {
			return "material " + std::to_string(m.id) + ": tc = " + capillary::format_value(m.tc) + ", en = " + capillary::format_value(m.en) + ", et = " + capillary::format_value(m.et)
			        + ", kn = " + capillary::format_value(m.kn) + ", cn = " + capillary::format_value(m.cn) + ", ks = " + capillary::format_value(m.ks) + ", cs = " + capillary::format_value(m.cs);
		};
		throw std::invalid_argument(
		        "PendularMat: give either tc, en, et or kn, cn, ks, cs on both materials (" + given(m1) + "; " + given(m2) + ")");
	}
	if (byTime) {
		const Real tc = (m1.tc + m2.tc) / 2, en = (m1.en + m2.en) / 2, et = (m1.et + m2.et) / 2;
		if (!(massR > 0))
			throw std::invalid_argument(
			        "PendularMat with tc, en, et: bodies need a positive mass (masses " + capillary::format_value(body1->state->mass) + " and "
			        + capillary::format_value(body2->state->mass) + " kg)");
		const Real omega = Mathr::PI / tc;                                            // half period of the damped oscillation = tc
		const Real x     = (m1.en == m2.en) ? m1.dampingRatioN : dampingRatioFor(en); // beta / omega
		phys->kn         = massR * omega * omega * (1 + x * x);
		phys->cn         = 2 * massR * omega * x;
		// Tangential: YADE's ViscElMat rule (Pournin2001 with the factor 2/7 of a rolling sphere).
		const Real xt = -math::log(et) / Mathr::PI;
		phys->ks      = 2. / 7. * massR * omega * omega * (1 + xt * xt);
		phys->cs      = 2. / 7. * 2 * massR * omega * xt;
	} else {
		auto series = [](Real a, Real b) { return (a > 0 && b > 0) ? a * b / (a + b) : 0; };
		phys->kn    = series(m1.kn, m2.kn);
		phys->cn    = series(m1.cn, m2.cn);
		phys->ks    = series(m1.ks, m2.ks);
		phys->cs    = series(m1.cs, m2.cs);
	}
	phys->tangensOfFrictionAngle = math::tan(math::min(m1.frictionAngle, m2.frictionAngle));
}

void Ip2_PendularMat_PendularMat_PendularPhys::setLiquid(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const PendularMat& m2, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	for (const auto& bm : { std::make_pair(body1, &m1), std::make_pair(body2, &m2) }) {
		const auto* state = dynamic_cast<const PendularState*>(bm.first->state.get());
		if (state && state->film > 0 && !bm.second->filmMode)
			throw std::invalid_argument("PendularState.film = " + capillary::format_value(state->film) + " m^3 on body " + std::to_string(bm.first->id)
			                            + ", whose material has liquid = '" + bm.second->liquid + "'; films need liquid = 'film'");
	}
	phys->wet = m1.wet && m2.wet;
	if (phys->wet) {
		auto mustMatch = [&](const char* name, const std::string& a, const std::string& b) {
			if (a != b)
				throw std::invalid_argument(
				        std::string("PendularMat.") + name + " must be equal on both materials of a bridge; got '" + a + "' and '" + b + "'");
		};
		mustMatch("model", m1.model, m2.model);
		if (m1.ruptureId != m2.ruptureId || m1.dynamicRupture != m2.dynamicRupture) mustMatch("rupture", m1.rupture, m2.rupture); // pitois = willett+pitois
		mustMatch("forceInContact", m1.forceInContact ? "True" : "False", m2.forceInContact ? "True" : "False");
		// Compared as values: 1e-7 and 4e-7 N are different, and the message shows both exactly.
		if (m1.linearFmax != m2.linearFmax) mustMatch("linearFmax", capillary::format_value(m1.linearFmax), capillary::format_value(m2.linearFmax));
		if (m1.linearKc != m2.linearKc) mustMatch("linearKc", capillary::format_value(m1.linearKc), capillary::format_value(m2.linearKc));
		mustMatch("calibrateFrom", m1.calibrateFrom, m2.calibrateFrom);
		mustMatch("extrapolate", m1.extrapolate ? "True" : "False", m2.extrapolate ? "True" : "False");
		if ((m1.eta > 0) != (m2.eta > 0))
			throw std::invalid_argument("PendularMat.eta must be > 0 on both materials of a viscous bridge or 0 on both; got " + capillary::format_value(m1.eta)
			                            + " and " + capillary::format_value(m2.eta) + " Pa s (the liquid's viscosity; a material left at 0 would halve it)");
		if (m1.eta > 0) {
			mustMatch("viscousNormal", m1.viscousNormal, m2.viscousNormal);
			if (m1.viscousSmin != m2.viscousSmin)
				mustMatch("viscousSmin", capillary::format_value(m1.viscousSmin), capillary::format_value(m2.viscousSmin));
		}
		phys->R1             = radiusOf(body1);
		phys->R2             = radiusOf(body2);
		phys->swapped        = math::isinf(phys->R1);
		if (phys->swapped) { // keep the sphere first: the kernels take R2 = inf for a wall
			std::swap(phys->R1, phys->R2);
			phys->theta1 = m2.theta;
			phys->theta2 = m1.theta;
		} else {
			phys->theta1 = m1.theta;
			phys->theta2 = m2.theta;
		}
		if (math::isinf(phys->R1)) throw std::invalid_argument("PendularMat: a liquid bridge needs at least one sphere");
		phys->Vb             = (m1.Vb + m2.Vb) / 2;
		phys->gamma          = (m1.gamma + m2.gamma) / 2;
		phys->modelIndex     = int(m1.modelId);
		phys->ruptureIndex   = int(m1.ruptureId);
		phys->calibrateIndex = int(m1.calibrateId);
		phys->extrapolate    = m1.extrapolate;
		phys->linearFmax     = m1.linearFmax;
		phys->linearKc       = m1.linearKc;
		phys->forceInContact = m1.forceInContact;
		phys->eta            = (m1.eta + m2.eta) / 2;
		phys->viscousIndex   = phys->eta > 0 ? int(m1.viscousId) : -1;
		phys->viscousSmin    = m1.viscousSmin;
		phys->dynamicRupture = m1.dynamicRupture; // both wet: validated with eta > 0
		if (m1.filmMode != m2.filmMode) mustMatch("liquid", m1.liquid, m2.liquid);
		if (!m1.filmMode) {
			phys->buildBridge();
			return;
		}
		mustMatch("formation", m1.formation, m2.formation);
		mustMatch("transfer", m1.transfer, m2.transfer);
		setFilm(phys, m1, body1, body2);
	}
}

// Film mode: the volume range of the pair's bridges, checked once with the largest (model, contact
// angles, size ratio, transfer rule); the bridge itself is built when it forms (settleFilms).
void Ip2_PendularMat_PendularMat_PendularPhys::setFilm(
        const shared_ptr<PendularPhys>& phys, const PendularMat& m1, const shared_ptr<Body>& body1, const shared_ptr<Body>& body2) const
{
	for (const auto& b : { body1, body2 })
		if (!dynamic_cast<const PendularState*>(b->state.get()))
			throw std::invalid_argument("PendularMat.liquid = 'film' needs a PendularState on body " + std::to_string(b->id) + ", which has a "
			                            + b->state->getClassName() + " (create it with utils.sphere(..., material=mat) or give it mat.newAssocState())");
	bool checked = false;
	for (const auto& e : scene->engines)
		if (dynamic_cast<const PendularCheck*>(e.get())) checked = true;
	if (!checked)
		throw std::invalid_argument("PendularMat.liquid = 'film' needs a PendularCheck engine after the interaction loop, which forms the bridges and "
		                            "moves the liquid at the end of each step (yade_capillary.scene.engines adds it)");
	for (const auto& b : { body1, body2 }) {
		const auto& st = static_cast<const PendularState&>(*b->state);
		if (math::isinf(radiusOf(b)) && st.film > 0 && !(st.filmArea > 0))
			throw std::invalid_argument("PendularState.film = " + capillary::format_value(st.film) + " m^3 on body " + std::to_string(b->id)
			                            + ", a wall or facet with filmArea = 0, which holds no liquid; give it the wettable area filmArea > 0 [m^2]");
	}
	phys->film          = true;
	phys->filmFormation = m1.filmFormation;
	phys->transferIndex = int(m1.transferId);
	// V* range: the model's domain (Plausible with extrapolate), and the exact transfer table's.
	Real r1, r2;
	capillary::equivalent_pair(phys->R1, phys->R2, r1, r2);
	const Real               R = capillary::harmonic_mean_radius(r1, r2); // of V* = V/R^3
	const capillary::Domain& d = capillary::info(capillary::Model(phys->modelIndex)).domain;
	Real vstarMin = phys->extrapolate ? capillary::Plausible::vstar_min : d.vstar_min, vstarMax = phys->extrapolate ? capillary::Plausible::vstar_max : d.vstar_max;
	if (m1.transferId == capillary::Transfer::exact) {
		vstarMin = math::max(vstarMin, math::exp(capillary::yltable::lnv_min));
		vstarMax = math::min(vstarMax, math::exp(capillary::yltable::lnv_max));
	}
	const Real R3 = R * R * R;
	phys->VbMin   = vstarMin * R3;
	phys->VbMax   = math::min(phys->Vb, vstarMax * R3);
	if (!(phys->VbMax >= phys->VbMin))
		capillary::out_of_range("PendularMat.Vb (the mean of the two materials)", phys->Vb, "[" + capillary::format_value(phys->VbMin) + ", inf) for this pair", "m^3",
		                        "with liquid='film' Vb is the largest bridge volume; the smallest is V* = " + capillary::format_value(vstarMin)
		                                + " times R^3 (the domain of the model and of the transfer rule)");
	// The largest bridge checks everything but its volume: model, angles, ratio, transfer rule.
	phys->Vb = phys->VbMax;
	phys->buildBridge();
	try {
		capillary::transfer_ratio(capillary::Transfer(phys->transferIndex), phys->R1, phys->R2, phys->Vb, phys->bridge.rupture, phys->theta1, phys->theta2);
	} catch (const std::exception& e) {
		throw std::invalid_argument("PendularMat.transfer = '" + m1.transfer + "' cannot split this pair's bridges (PendularMat.theta " + capillary::format_value(phys->theta1)
		                            + " and " + capillary::format_value(phys->theta2) + " rad, radii " + capillary::format_value(phys->R1) + " and "
		                            + capillary::format_value(phys->R2) + " m): " + e.what() + "; another rule: " + capillary::transfer_names());
	}
	phys->Vb = 0;
	phys->viscous.reset();
}

namespace {
	// Forces of YADE's InteractionLoop: straight into the scene's force container.
	struct SceneSink {
		Scene*     scene;
		Body::id_t id1, id2;
		bool       enabled; // Interaction::isActive
		void       force(const Vector3r& f) const
		{
			if (!enabled) return;
			scene->forces.addForce(id1, -f);
			scene->forces.addForce(id2, f);
		}
		void forceTorque(const Vector3r& f, const Vector3r& t1, const Vector3r& t2) const
		{
			if (!enabled) return;
			force(f);
			scene->forces.addTorque(id1, t1);
			scene->forces.addTorque(id2, t2);
		}
	};
} // namespace

namespace {
	PendularState& filmOf(Scene* scene, Body::id_t id) { return static_cast<PendularState&>(*Body::byId(id, scene)->state); }
} // namespace

bool Law2_ScGeom_PendularPhys_Bridge::filmsTouch(const PendularPhys& phys, const PendularKinematics& k, Real gap) const
{
	const FilmPair       ids    = filmPair(phys, k.id1, k.id2);
	const PendularState& sphere = filmOf(scene, ids.sphere);
	const PendularState& other  = filmOf(scene, ids.other);
	return gap <= sphere.thickness(phys.R1) + other.thickness(phys.R2);
}

void Law2_ScGeom_PendularPhys_Bridge::askFormation(PendularPhys& phys, const PendularKinematics& k)
{
	// Shi & McCarthy (Elskamp2018 eq. 8; eq. 9-10 with a wall) from the films at the start of the step.
	const FilmPair       ids    = filmPair(phys, k.id1, k.id2);
	const PendularState& sphere = filmOf(scene, ids.sphere);
	const PendularState& other  = filmOf(scene, ids.other);
	const Real           fromSphere = capillary::film_contribution(phys.R1, phys.R2, sphere.film);
	const Real           fromOther  = math::isinf(phys.R2) ? capillary::wall_film_contribution(phys.R1, other.thickness(phys.R2))
	                                                       : capillary::film_contribution(phys.R2, phys.R1, other.film);
	// Too little liquid for a bridge (even before sharing the films): no request, the pair stays dry.
	if (!(fromSphere + fromOther >= phys.VbMin)) return;
	phys.pending = true;
	const std::lock_guard<std::mutex> lock(filmMutex);
	formations.push_back({ &phys, k.id1, k.id2, phys.swapped ? fromOther : fromSphere, phys.swapped ? fromSphere : fromOther, k.owned });
}

void Law2_ScGeom_PendularPhys_Bridge::settleFilms(Scene* current)
{
	if (formations.empty() && returns.empty()) return;
	// In the order of the pairs, whatever the order of the threads: a run is reproducible.
	std::sort(formations.begin(), formations.end(), [](const FilmFormation& a, const FilmFormation& b) {
		return std::make_pair(a.id1, a.id2) < std::make_pair(b.id1, b.id2);
	});
	// A film asked for more than it holds is shared in proportion to the requests (Elskamp2018
	// section 2.2.1: all the bridges of one step form under the same conditions).
	std::unordered_map<Body::id_t, Real> share; // per body: the sum of the requests, then the share granted
	for (const auto& f : formations) {
		share[f.id1] += f.take1;
		share[f.id2] += f.take2;
	}
	for (auto& s : share) {
		const Real demand = s.second, film = current->bodies->exists(s.first) ? filmOf(current, s.first).film : 0;
		s.second = demand > film ? film / demand : 1;
	}
	std::string error;
	for (const auto& f : formations) {
		// An engine between the loop and PendularCheck may have removed the pair or a body: nothing
		// was taken from the films yet, so the request is simply dropped.
		if (!current->bodies->exists(f.id1) || !current->bodies->exists(f.id2)) continue;
		const shared_ptr<Interaction>& I = current->interactions->find(f.id1, f.id2);
		if (!I || I->phys.get() != f.phys || !f.phys->pending) continue;
		PendularPhys&  phys = *f.phys;
		PendularState& s1   = filmOf(current, f.id1);
		PendularState& s2   = filmOf(current, f.id2);
		phys.pending        = false;
		Real v1 = f.take1 * share[f.id1], v2 = f.take2 * share[f.id2];
		if (v1 + v2 > phys.VbMax) { // capped: the rest stays on the films
			const Real scale = phys.VbMax / (v1 + v2);
			v1 *= scale;
			v2 *= scale;
		}
		v1 = math::min(v1, s1.film); // the shares hold to rounding: never more than the film
		v2 = math::min(v2, s2.film);
		if (!(v1 + v2 >= phys.VbMin)) continue;
		phys.Vb = v1 + v2;
		try {
			phys.buildBridge();
			phys.transfer1 = capillary::transfer_ratio(
			        capillary::Transfer(phys.transferIndex), phys.R1, phys.R2, phys.Vb, phys.bridge.rupture, phys.theta1, phys.theta2);
		} catch (const std::exception& e) {
			phys.Vb = 0;
			if (error.empty()) error = std::string(e.what()) + " (bridge " + std::to_string(f.id1) + "-" + std::to_string(f.id2) + " not formed)";
			continue;
		}
		s1.film -= v1;
		s2.film -= v2;
		phys.active = true;
		if (f.owned) {
			nBridges += 1;
			liquidVolume += phys.Vb;
			liquidFormed += phys.Vb;
		}
	}
	formations.clear();
	for (const auto& r : returns) {
		if (current->bodies->exists(r.id)) filmOf(current, r.id).film += r.volume;
		else liquidRemoved += r.volume;
	}
	returns.clear();
	if (!error.empty()) throw std::invalid_argument(error);
}

namespace {
	void refuseWhileRunning(const char* what)
	{
		if (Omega::instance().isRunning())
			throw std::runtime_error(std::string(what) + " while the simulation runs (O.run()): the bridges and films change under it; call O.pause() or O.wait() first");
	}
} // namespace

void Law2_ScGeom_PendularPhys_Bridge::releasePair(Scene* current, Interaction& I)
{
	auto* phys = dynamic_cast<PendularPhys*>(I.phys.get());
	if (!phys || !phys->active) return;
	refuseWhileRunning("removing a bridge");
	const Body::id_t id1 = I.getId1(), id2 = I.getId2();
	const bool       both = current->bodies->exists(id1) && current->bodies->exists(id2);
	if (!both || pendularOwner(current->subdomain, Body::byId(id1, current)->subdomain, Body::byId(id2, current)->subdomain)) {
		nBridges -= 1;
		liquidVolume -= phys->Vb;
		liquidReleased += phys->Vb;
		zeroEmptyTotals();
	}
	phys->active = false; // the interaction goes (or becomes potential) without the law
	if (!phys->film) return;
	// As a rupture; a share of a body that no longer exists leaves the scene.
	const FilmPair ids        = filmPair(*phys, id1, id2);
	const bool     otherHolds = !current->bodies->exists(ids.other) || filmOf(current, ids.other).holds(phys->R2);
	const Real     toSphere   = sphereShare(*phys, otherHolds);
	for (const auto& share : { std::make_pair(ids.sphere, toSphere), std::make_pair(ids.other, phys->Vb - toSphere) }) {
		if (current->bodies->exists(share.first)) filmOf(current, share.first).film += share.second;
		else liquidRemoved += share.second;
	}
	phys->Vb = 0;
}

void Law2_ScGeom_PendularPhys_Bridge::zeroEmptyTotals()
{
	if (nBridges.get() == 0) liquidVolume.reset();
}

Law2_ScGeom_PendularPhys_Bridge::OverlapReport Law2_ScGeom_PendularPhys_Bridge::takeOverlaps()
{
	const std::lock_guard<std::mutex> lock(overlapMutex);
	const OverlapReport               report = overlaps;
	overlaps                                 = OverlapReport {};
	return report;
}

void Law2_ScGeom_PendularPhys_Bridge::overlapSeen(Real depth, Body::id_t id1, Body::id_t id2, Real kn)
{
	const shared_ptr<Body>& b1 = Body::byId(id1, scene);
	const shared_ptr<Body>& b2 = Body::byId(id2, scene);
	if (heavy(*b1) && heavy(*b2)) return; // e.g. fixed spheres placed overlapping: no collision
	const Real radius = math::min(radiusOf(b1), radiusOf(b2));
	if (!(depth > overlapBound * radius)) return;
	// The normal speed at impact, from the energy of the undamped spring now: v0^2 = v^2 + kn d^2/m.
	const shared_ptr<Interaction> I      = scene->interactions->find(id1, id2);
	const bool                    shift  = scene->isPeriodic && I;
	const Vector3r                pos2   = b2->state->pos + (shift ? scene->cell->intrShiftPos(I->cellDist) : Vector3r::Zero());
	const Vector3r                vel2   = b2->state->vel + (shift ? scene->cell->intrShiftVel(I->cellDist) : Vector3r::Zero());
	const bool spheres = dynamic_cast<const Sphere*>(b1->shape.get()) && dynamic_cast<const Sphere*>(b2->shape.get());
	// Two spheres: along the centres; with a wall or facet: the relative speed (a bound on its normal part).
	const Real vn = spheres ? (pos2 - b1->state->pos).normalized().dot(b1->state->vel - vel2) : (b1->state->vel - vel2).norm();
	const Real speed = math::sqrt(vn * vn + kn * depth * depth / effectiveMass(*b1, *b2));
	const std::lock_guard<std::mutex> lock(overlapMutex);
	++overlaps.count;
	if (depth / radius > overlaps.largest) {
		overlaps.largest = depth / radius;
		overlaps.id1     = id1;
		overlaps.id2     = id2;
		overlaps.overlap = depth;
		overlaps.radius  = radius;
		overlaps.speed   = speed;
	}
}

void Law2_ScGeom_PendularPhys_Bridge::eraseBody(Scene* current, Body::id_t id, bool clumpMembers)
{
	if (!current->bodies->exists(id)) return;
	const shared_ptr<Body> body = (*current->bodies)[id];
	if (clumpMembers && body->isClump()) // its members point at it (Clump::members is not exported by YADE's library)
		for (const auto& b : *current->bodies)
			if (b && b->isClumpMember() && b->clumpId == id) eraseBody(current, b->id, false);
	// Its bridges break as at rupture (the partners keep their shares); then its film, with its own
	// shares, leaves the scene.
	for (const auto& entry : body->intrs) releasePair(current, *entry.second);
	if (auto* state = dynamic_cast<PendularState*>(body->state.get())) {
		if (state->film > 0) refuseWhileRunning("O.bodies.erase of a body with a film");
		liquidRemoved += state->film;
	}
}

void Law2_ScGeom_PendularPhys_Bridge::clearBodies(Scene* current)
{
	for (const auto& I : *current->interactions) releasePair(current, *I);
	for (const auto& b : *current->bodies)
		if (b)
			if (auto* state = dynamic_cast<PendularState*>(b->state.get())) liquidRemoved += state->film;
}

void Law2_ScGeom_PendularPhys_Bridge::formBridge(Body::id_t id1, Body::id_t id2, Real pastRupture)
{
	refuseWhileRunning("formBridge()");
	const auto&       current = Omega::instance().getScene();
	const std::string pair    = "formBridge(id1=" + std::to_string(id1) + ", id2=" + std::to_string(id2) + "): ";
	if (!(pastRupture >= 0 && math::isfinite(pastRupture)))
		throw std::invalid_argument(pair + "pastRupture = " + capillary::format_value(pastRupture) + " m; allowed: a finite value >= 0 m");
	PendularLoop::syncScene(current.get(), true); // the loop reads the changed objects at its next step
	const shared_ptr<Interaction> I = current->interactions->find(id1, id2);
	if (!I || !I->isReal()) throw std::invalid_argument(pair + "no real interaction between these bodies (utils.createInteraction makes one)");
	auto* phys = dynamic_cast<PendularPhys*>(I->phys.get());
	auto* geom = dynamic_cast<const ScGeom*>(I->geom.get());
	if (!phys || !geom) throw std::invalid_argument(pair + "the interaction has no ScGeom and PendularPhys");
	if (!phys->wet || phys->modelIndex < 0) throw std::invalid_argument(pair + "the materials are dry (PendularMat.wet = False) or the bridge's liquid was rejected");
	if (phys->film) throw std::invalid_argument(pair + "liquid='film': a film-mode bridge takes its liquid from the films, not from a saved state");
	if (phys->active) throw std::invalid_argument(pair + "the interaction already has a bridge");
	const Real gap = -geom->penetrationDepth;
	if (!(gap <= phys->bridge.rupture + pastRupture))
		throw std::invalid_argument(pair + "gap = " + capillary::format_value(gap) + " m is beyond the rupture distance; allowed: gap <= "
		                            + capillary::format_value(phys->bridge.rupture) + " m + pastRupture (" + capillary::format_value(pastRupture) + " m)");
	phys->active = true;
	if (pendularOwner(current->subdomain, Body::byId(id1, current)->subdomain, Body::byId(id2, current)->subdomain)) {
		nBridges += 1;
		liquidVolume += phys->Vb;
		liquidFormed += phys->Vb;
	}
}

boost::python::dict Law2_ScGeom_PendularPhys_Bridge::liquidTotals() const
{
	refuseWhileRunning("liquidTotals()");
	const auto& current = Omega::instance().getScene();
	Real        films = 0, bridges = 0, fixedBridges = 0;
	for (const auto& b : *current->bodies)
		if (b)
			if (const auto* s = dynamic_cast<const PendularState*>(b->state.get())) films += s->film;
	for (const auto& I : *current->interactions)
		if (const auto* p = dynamic_cast<const PendularPhys*>(I->phys.get()))
			if (p->active) (p->film ? bridges : fixedBridges) += p->Vb;
	boost::python::dict d;
	d["films"]        = films;
	d["bridges"]      = bridges;
	d["removed"]      = liquidRemoved;
	d["total"]        = films + bridges + liquidRemoved;
	d["fixedBridges"] = fixedBridges;
	return d;
}

bool Law2_ScGeom_PendularPhys_Bridge::go(shared_ptr<IGeom>& ig, shared_ptr<IPhys>& ip, Interaction* I)
{
	const auto      id1 = I->getId1(), id2 = I->getId2();
	const Body&     b1  = *Body::byId(id1, scene);
	const Body&     b2  = *Body::byId(id2, scene);
	const State&    de1 = *b1.state;
	const State&    de2 = *b2.state;
	const bool      periodic = scene->isPeriodic;
	const Vector3r  shift2   = periodic ? scene->cell->intrShiftPos(I->cellDist) : Vector3r::Zero();
	const Vector3r  shiftVel = periodic ? scene->cell->intrShiftVel(I->cellDist) : Vector3r::Zero();
	const PendularKinematics k { de1.pos, de1.vel, de1.angVel, de2.pos, de2.vel, de2.angVel, shift2, shiftVel,
		                     pendularOwner(scene->subdomain, b1.subdomain, b2.subdomain), id1, id2 };
	SceneSink       sink { scene, id1, id2, I->isActive };
	const ScGeom&   geom   = static_cast<const ScGeom&>(*ig);
	const auto      rotate = [&geom](Vector3r& v) { geom.rotate(v); };
	return apply(geom, static_cast<PendularPhys&>(*ip), k, scene->dt, rotate, sink);
}

} // namespace yade
