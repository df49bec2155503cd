// The plugin's integration with YADE's Python side (PythonSide.cpp): how an error raised in a step
// reaches Python, and the wrappers of yade.wrapper's methods that need the plugin's help.
#pragma once

#include "YadeHeaders.hpp"

#include <string>

namespace yade {
namespace pendular {
	// Keeps `message`, about to be thrown from a step of `loop` (the scene of a step run by YADE's
	// simulation thread; nullptr for O.step(), which runs in the Python thread), so that O.run(n, True)
	// and O.wait() raise it as the ValueError that O.step() gives, also when YADE's wait() missed it.
	void rememberRaised(const std::string& message, Scene* loop);
	// Wraps yade.wrapper's Omega.run and Omega.wait, once, so that they raise an error of a step that
	// YADE's wait() missed, and the erase and clear of BodyContainer and InteractionContainer, so that
	// the liquid they remove is accounted for. Called by yade_capillary.patches.install (through
	// PendularCheck.installGuards), which lists every patch of YADE's Python objects.
	void installGuards();
	// Whether installGuards has run in this process (read by the simulation thread).
	bool guardsInstalled();
} // namespace pendular
} // namespace yade
