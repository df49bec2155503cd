// PendularLoop's instrumentation, out of line (see LoopInstrumentation.hpp): the memory figures of
// PendularLoop.memory().
#include "LoopInstrumentation.hpp"
#include "LoopBodies.hpp"
#include "LoopPairs.hpp"
#include "LoopRecords.hpp"

#include <pkg/dem/ViscoelasticCapillarPM.hpp>

namespace yade {
namespace pendular {
	boost::python::dict loopMemory()
	{
		boost::python::dict d;
		d["Interaction"]   = sizeof(Interaction);
		d["ScGeom"]        = sizeof(ScGeom);
		d["PendularPhys"]  = sizeof(PendularPhys);
		d["ViscElCapPhys"] = sizeof(ViscElCapPhys);
		d["particle"]      = 2 * sizeof(Particle); // this step's and the last one's (see BodySnapshot::previous)
		d["epoch"]         = sizeof(Near);
		d["slot"]          = sizeof(Slot);
		d["record"]        = sizeof(Record) + sizeof(shared_ptr<Interaction>); // with its entry of RecordStore::interactions
		d["invariants"]    = sizeof(Invariants) + sizeof(PendularPhys); // once per distinct set of bridge and contact parameters, with its prototype
		d["forces"]        = 2 * sizeof(Vector3r);
		return d;
	}
} // namespace pendular
} // namespace yade
