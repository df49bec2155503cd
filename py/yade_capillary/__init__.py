"""yade-capillary: wet (pendular) granular matter for YADE.

Public modules:
    kernels  -- the pure capillary bridge models (C++, pybind11): force, bridge, rupture_distance
    cases    -- case tables (Gladkyy & Schwarze 2014, Table 1; Elskamp & Kruggel-Emden 2018, Fig. 5a, 5b)
    scene    -- helpers that build YADE engine lists for the plugin's functors (inside yade only)
    patches  -- every patch of YADE's Python objects, what each guards, and install() (engines() calls it; inside yade only)
    twosphere -- two-sphere and sphere-wall pull-offs, also viscous at constant speed (inside yade only)
    liquid   -- liquid accounting of film mode by population, CSV and VTK output
    mpi      -- YADE's MPI module (yade.mpy) with the plugin: slabs of ranks, liquid totals over the ranks (inside yade only)
    plots    -- matplotlib figures (PNG)
    shearcell -- the split-bottom ring shear cell: configurations, preparation, runs (also in segments), snapshots (inside yade only)
    cellanalysis -- the shear-cell analysis: coarse-grained fields, band and tau-p fits, contacts against the gap
    cg       -- axisymmetric coarse-graining (density, angular velocity, contact and kinetic stress) for rotating flows
    fits     -- erf shear-band fit and tau = mu p + c fit with standard errors

The compiled module is yade_capillary._kernels (re-exported by kernels); the build assembles the
package in build/python, so PYTHONPATH=build/python gives all of it in plain python3. Developer tools
are not part of the package: the benchmarks are in bench/, the test support in tests/support/, the
helpers of the studies beside their scripts in scripts/studies/.
"""
