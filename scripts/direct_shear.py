# Richefeu et al. 2008's direct shear test (section 3.2): the residual shear stress of a split cylinder of
# glass beads for each water content and normal stress, and the Mohr-Coulomb c and phi per water content.
#   build/yade-capillary -j2 -n -x scripts/direct_shear.py OUTDIR [config] [--w 0,0.0005,0.001,0.01,0.02]
#              [--sigma 300,600,900] [--protocol particles] [--dry 0] [--speed 1] [--packing PATH]
# Writes OUTDIR/runs.csv (one line per test), OUTDIR/mohr_coulomb.csv (c, phi per water content, against the
# normal stress on the shear plane) and OUTDIR/w<w>_sigma<sigma>/shear.csv (stresses against displacement).
# A test whose summary.json exists is read, not run again, so an interrupted series goes on where it stopped. The
# settled packing, OUTDIR/settled_<config>.yade.gz, is kept: --packing starts other series from it.
import argparse
import sys

from yade_capillary import directshear as ds

floats = lambda s: [float(x) for x in s.split(",")]
p = argparse.ArgumentParser(prog="direct_shear.py", description="Richefeu 2008's direct shear series")
p.add_argument("outdir")
p.add_argument("config", nargs="?", default="ci", choices=sorted(ds.CONFIGS), help="ci (minutes) or paper")
p.add_argument("--w", type=floats, default=[0.0, 0.01], help="water contents [-], comma-separated")
p.add_argument("--sigma", type=floats, help="lid stresses [Pa]; the configuration's by default (ci: 10,300; paper: 300,600,900)")
p.add_argument("--protocol", default="particles", help="PendularBonds.protocol")
p.add_argument("--dry", type=float, default=0.0, help="fraction of the pairs kept dry [-]")
p.add_argument("--speed", type=float, default=1.0, help="times the shear speed of the configuration's inertial number")
p.add_argument("--packing", help="start from this settled packing (OUTDIR/settled_<config>.yade.gz of another series) instead of OUTDIR's")
a = p.parse_args(sys.argv[1:])
ds.series(a.config, a.w, a.sigma or list(ds.CONFIGS[a.config]["sigmas"]), a.outdir, a.protocol, a.dry, a.speed, packing=a.packing)
