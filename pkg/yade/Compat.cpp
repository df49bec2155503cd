// Symbols referenced by the YADE 2025.2.0 headers but absent from Debian's YADE 2023.02a.
// Cell's inline Python registration names this member; the plugin never calls it. A weak
// definition lets the dynamic linker prefer YADE's own, should a newer YADE define it.
#include <core/Cell.hpp>

namespace yade {
__attribute__((weak)) Vector3r Cell::bodyFluctuationVelPy(const shared_ptr<Body>&) { return Vector3r::Zero(); }
} // namespace yade
