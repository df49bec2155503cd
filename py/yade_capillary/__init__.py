"""yade-capillary: wet (pendular) granular matter for YADE.

Modules:
    kernels  -- the pure capillary bridge models (C++, pybind11): force, bridge, rupture_distance
    cases    -- case tables (Gladkyy & Schwarze 2014, Table 1; Elskamp & Kruggel-Emden 2018, Fig. 5a, 5b)
    scene    -- helpers that build YADE engine lists for the plugin's functors (inside yade only)
    patches  -- every patch of YADE's Python objects, what each guards, and install() (engines() calls it; inside yade only)
    objects  -- guard(): the patches PendularLoop's records need, under the name its docstrings give (inside yade only)
    twosphere -- two-sphere and sphere-wall pull-offs, also viscous at constant speed (inside yade only)
    plots    -- matplotlib figures (PNG)
    accuracy -- error and cost of every model against the Young-Laplace solver
    mixedangles -- unequal contact angles: mean of cosines vs cosine of the mean angle, against the solver
    benchmark -- side-by-side speed of our Law2 and YADE's built-in capillary law (inside yade)
    cg       -- axisymmetric coarse-graining (density, angular velocity, stress) for rotating flows
    fits     -- erf shear-band fit and tau = mu p + c fit with standard errors
    fuzz     -- randomised stress test of the kernels (every model, wide and absurd inputs)
    stress   -- wet scenes, time-step limit and invariant checks for the in-YADE stress tests (inside yade only)
    reference -- the class reference docs/reference.md, from the build's docstrings (inside yade only)
    random_scenes -- random wet scenes as a new user builds them, for the stability campaign (inside yade only)

The compiled module is yade_capillary._kernels (re-exported by kernels); the build assembles the
package in build/python, so PYTHONPATH=build/python gives all of it in plain python3.
"""
