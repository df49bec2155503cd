// The classes of yade-capillary's YADE layer, for the files that use several of them (PendularLoop,
// the engines): material and body state, interaction physics, Ip2, contact law and PendularCheck.
// The capillary formulas live in pkg/kernels; each class has its own header here.
#pragma once

#include "Ip2_PendularMat_PendularMat_PendularPhys.hpp"
#include "Law2_ScGeom_PendularPhys_Bridge.hpp"
#include "PendularCheck.hpp"
#include "PendularMat.hpp"
#include "PendularPhys.hpp"
#include "PendularState.hpp"
