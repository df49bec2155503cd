// PendularLoop's body snapshot: what its pass reads of each body, gathered once per step into a
// contiguous array (Particle: two cache lines per body) instead of two shared_ptr hops to a State per
// interaction; the array of the pass before, from which the records' shearInc follows (see
// RecordStore::shearIncOf); and what PendularIntegrator reads of every body in the same step
// (pendular::BodyPointers). BodySnapshot owns these arrays and writes a gathered body into them;
// BodyReader turns one Body into a Particle. The loop over the bodies is PendularLoop::gather's, which
// does the gap bound's and the force reset's work per body in the same pass (one read of each Body).
// Everything here is per body and step: inline.
#pragma once

#include "LoopInstrumentation.hpp"
#include "Passes.hpp"
#include "Pendular.hpp"

#include <pkg/common/Facet.hpp>
#include <pkg/common/Sphere.hpp>
#include <pkg/common/Wall.hpp>

#include <cstdint>
#include <typeinfo>
#include <vector>

namespace yade {
namespace pendular {
	// The loop's passes are bound by memory latency (see prefetchObject): they prefetch the bodies, the
	// interactions and the records this many entries ahead (an Interaction and a Body, whose objects are
	// read once it is cached, twice as far).
	constexpr long prefetchAhead = 8;

	// What the fused pass needs of one body. Two whole cache lines: what every bridge-step and every check
	// of a potential pair reads (position, velocity, radius, subdomain, kind) in the first, what only
	// friction and films read in the second; whole lines, so that the bodies that other threads read can be
	// written with streaming stores (see BodySnapshot::store).
	struct alignas(64) Particle {
		enum Kind : uint8_t { missing, other, clump, pendularSphere, pendularBoundary };
		Vector3r pos, vel;
		Real     radius;
		int      subdomain;
		uint8_t  kind;
		Vector3r angVel;
		Real     reach; // film thickness of a sphere whose bridges form when the films touch (formation='films'), else 0
		// An id without a body (erased), also the value of new entries (the sweep compares before it writes).
		static Particle none() { return Particle { Vector3r::Zero(), Vector3r::Zero(), 0, 0, missing, Vector3r::Zero(), 0 }; }
		// Takes p's values, writing each line only if it changes: a body that does not move costs a read, and
		// the second line of a sphere that does not spin (frictionless) is not written. (A line that another
		// thread read in the last pass is written only after that core's copy is invalidated.)
		void update(const Particle& p)
		{
			if (!(pos == p.pos && vel == p.vel && radius == p.radius && subdomain == p.subdomain && kind == p.kind)) {
				pos       = p.pos;
				vel       = p.vel;
				radius    = p.radius;
				subdomain = p.subdomain;
				kind      = p.kind;
			}
			if (!(angVel == p.angVel && reach == p.reach)) {
				angVel = p.angVel;
				reach  = p.reach;
			}
		}
	};
	static_assert(sizeof(Particle) == 128 && alignof(Particle) == 64, "a Particle is two whole cache lines (see streamStore)");

	// Turns a Body into a Particle. It keeps what it found of the last material and the last shape's class,
	// so that a run of bodies with the same ones costs no virtual call per body: one reader per thread
	// (firstprivate), which reads the bodies of its part in order.
	class BodyReader {
	public:
		__attribute__((always_inline)) Particle read(const Body* b)
		{
			// Value-initialized: streamStore copies whole lines, padding included (never read), which GCC would
			// otherwise warn may be uninitialized.
			Particle p {};
			if (!b) {
				p = Particle::none();
				return p;
			}
			const State& s = *b->state;
			p.pos          = s.pos;
			p.vel          = s.vel;
			p.angVel       = s.angVel;
			p.subdomain    = b->subdomain;
			p.radius       = 0;
			p.reach        = 0;
			// The material's class, once per run of bodies with the same material (a virtual call per body
			// otherwise); held while it is the last one, so that no other object can take its address.
			if (b->material.get() != lastMaterial) {
				heldMaterial = b->material;
				lastMaterial = heldMaterial.get();
				lastPendular = lastMaterial && lastMaterial->getClassIndex() == pendularIndex;
			}
			if (b->isClump()) p.kind = Particle::clump;
			else if (!b->shape || !lastPendular)
				p.kind = Particle::other;
			else {
				const Shape&          shapeObject = *b->shape;
				const std::type_info& shapeType   = typeid(shapeObject);
				if (&shapeType != lastShapeType) {
					lastShapeType  = &shapeType;
					lastShapeIndex = shapeObject.getClassIndex();
				}
				const int shape = lastShapeIndex;
				if (shape == sphereIndex) {
					p.kind   = Particle::pendularSphere;
					p.radius = static_cast<const Sphere&>(*b->shape).radius;
					// Only materials whose bridges form when the films touch reach beyond the surface.
					if (static_cast<const PendularMat&>(*b->material).filmFormation)
						if (const auto* film = dynamic_cast<const PendularState*>(&s)) p.reach = film->thickness(p.radius);
				} else
					p.kind = (shape == wallIndex || shape == facetIndex) ? Particle::pendularBoundary : Particle::other;
			}
			return p;
		}

	private:
		const int sphereIndex = Sphere::getClassIndexStatic(), pendularIndex = PendularMat::getClassIndexStatic();
		const int wallIndex = Wall::getClassIndexStatic(), facetIndex = Facet::getClassIndexStatic();
		const Material*      lastMaterial = nullptr;
		bool                 lastPendular = false;
		shared_ptr<Material> heldMaterial;
		// The class index of the last shape's class, by its dynamic type (typeid reads the vtable that the object
		// points to): Shape::getClassIndex is a virtual call into libyade per body otherwise, which the compiler
		// cannot inline (docs/performance.md, "Per-body checks without two calls into libyade"). type_info objects
		// are static: an address seen once is never another class's.
		const std::type_info* lastShapeType  = nullptr;
		int                   lastShapeIndex = -1;
	};

	struct BodySnapshot {
		std::vector<Particle> particles;
		// The particles of the pass before (begin swaps the two arrays): with the time step and Ig2's
		// avoidGranularRatcheting of that pass, what the shearInc of a record in contact follows from.
		std::vector<Particle> previous;
		BodyPointers          pointers;
		// No body's kind or subdomain changed since the last pass (the records' bodies then need no check).
		bool kindsKept = false;

		// Before a gathering of n bodies, whose per-body passes the threads share by `parts` (see partOf).
		void begin(std::size_t n, const std::vector<long>& parts)
		{
			particles.swap(previous); // the last pass's particles stay readable for the records' shearInc
			particles.resize(n, Particle::none());
			pointers.scene = nullptr; // valid once the pass is complete
			pointers.parts = parts;
			pointers.states.resize(n);
			pointers.bounds.resize(n);
		}
		// Prefetches what the gathering reads of body id + ahead, in two levels: the Body, then, once it is
		// cached, its State and Shape (a sphere's radius is on the Shape's second cache line).
		static __attribute__((always_inline)) void prefetch(const std::vector<shared_ptr<Body>>& bodies, std::size_t id, std::size_t ahead)
		{
			const std::size_t n = bodies.size();
			if (id + 2 * ahead < n && bodies[id + 2 * ahead]) prefetchObject(bodies[id + 2 * ahead].get());
			if (id + ahead < n && bodies[id + ahead]) {
				const Body& next = *bodies[id + ahead];
				prefetchObject(next.state.get());
				__builtin_prefetch(next.shape.get());
				__builtin_prefetch(reinterpret_cast<const char*>(next.shape.get()) + 64);
			}
		}
		// Writes the particle of body id: with streaming stores if other threads read it in the pass (stream),
		// else line by line where it changed. Returns stream (the caller then fences before the barrier).
		__attribute__((always_inline)) bool store(std::size_t id, const Particle& p, bool stream)
		{
			if (stream) streamStore(particles[id], p);
			else
				particles[id].update(p);
			return stream;
		}
		// After the gathering: what PendularIntegrator may take from it in this step.
		void finish(const void* scene, long iter, int clumps, int aspherical, int subdomains)
		{
			pointers.clumps     = clumps;
			pointers.aspherical = aspherical;
			pointers.subdomains = subdomains;
			pointers.iter       = iter;
			pointers.scene      = scene;
		}
		// A body that records may join: a PendularMat sphere of subdomain `subdomain` (as gathered this step).
		bool sphereHere(Body::id_t id, int subdomain) const
		{
			const Particle& p = particles[id];
			return p.kind == Particle::pendularSphere && p.subdomain == subdomain;
		}
		long heldBytes() const
		{
			return capacityBytes(particles) + capacityBytes(previous) + capacityBytes(pointers.states) + capacityBytes(pointers.bounds)
			        + capacityBytes(pointers.parts);
		}
	};
} // namespace pendular
} // namespace yade
