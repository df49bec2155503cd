// YADE headers used by the plugin, precompiled once (they dominate the compile time).
#pragma once
#include <core/Body.hpp>
#include <core/Dispatching.hpp>
#include <core/Material.hpp>
#include <core/Omega.hpp>
#include <core/Scene.hpp>
#include <core/State.hpp>
#include <lib/base/openmp-accu.hpp>
#include <lib/high-precision/Constants.hpp>
#include <pkg/common/NormShearPhys.hpp>
#include <pkg/common/Sphere.hpp>
#include <pkg/dem/ScGeom.hpp>
