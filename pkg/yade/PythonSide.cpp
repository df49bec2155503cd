// The plugin's integration with YADE's Python side: PendularCheck's errors raised as ValueError also
// when YADE's O.run(n, True) and O.wait() miss or retype them, and the Python methods that remove
// bodies or interactions wrapped so that the liquid they remove is accounted for.
#include "PythonSide.hpp"
#include "Law2_ScGeom_PendularPhys_Bridge.hpp"
#include "PendularLoop.hpp"

#include <core/InteractionLoop.hpp>

#include <boost/python/exception_translator.hpp>
#include <boost/python/raw_function.hpp>
#include <boost/weak_ptr.hpp>
#include <atomic>
#include <mutex>
#include <stdexcept>
#include <string>
#include <typeinfo>

namespace yade {

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
	std::atomic<bool> guarded { false }; // installGuards has run

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
} // namespace

void pendular::rememberRaised(const std::string& message, Scene* loop)
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

bool pendular::guardsInstalled() { return guarded; }

void pendular::installGuards()
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

} // namespace yade
