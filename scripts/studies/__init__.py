"""Helpers of the studies whose scripts are in scripts/ (the cause analysis of the shear-cell results, the
accuracy of the models, unequal contact angles, the exact solver's domain); not part of the yade_capillary package. A script finds
them as `studies` next to itself: plain python3 puts the script's folder on sys.path, a script run by
yade inserts it (sys.argv[0] is the script there).

Modules:
    cell_configs  -- the shear-cell configurations of the studies (registered in shearcell.CONFIGS)
    cell_study    -- the studies' shear-cell analysis: the pipeline's fits plus their conventions, torque balance
    cell_closure  -- torque balance of cylinders: walls inside, contacts crossing, CG torque flux
    cell_fits     -- the fit under other conventions, block fits, the excess shear stress over the dry band
    cell_contacts -- contacts against the gap in classes, wet over dry counts, mean force against the model
    cell_stress_parts -- the band's stress split into bridges, contacts and kinetic part
    cell_report   -- a Markdown and CSV comparison of analysed runs with Gladkyy 2014
    accuracy      -- error and cost of every model against the Young-Laplace solver
    mixedangles   -- unequal contact angles: mean of cosines vs cosine of the mean angle, against the solver
    bridgedomain  -- the largest volume the Young-Laplace solver follows from contact to rupture, and why
    closedformerrors -- every closed-form model and rupture rule against the exact bridge beyond their range
    tableaccuracy -- young_laplace_table against the Young-Laplace solver over its whole domain
"""
