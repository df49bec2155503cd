# Speed of the small (ci) shear cell, wet (13.6 nl): our Law2 (willett_full) against YADE's
# built-in Law2_ScGeom_ViscElCapPhys_Basic (Willett_numeric), same positions and time step, in
# one run. A benchmark, not a test.
# Run:  build/yade-capillary -j1 -n -x scripts/benchmark_shear_cell.py [steps]
import sys

from yade_capillary import benchmark

steps = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
builtin, ours = benchmark.shear_cell(steps)
print("shear cell (ci, wet13.6nl), %d steps: built-in %.3g, ours %.3g particle-steps/s; ratio ours/built-in %.3f"
      % (steps, builtin["particle_steps_per_s"], ours["particle_steps_per_s"], ours["particle_steps_per_s"] / builtin["particle_steps_per_s"]))
sys.exit(0)
