/* ----------------------------------------------------------------------
   The impact deck's compute motion/2d as a LAMMPS plugin, for builds with
   the PLUGIN package: "plugin load impact_2d_plugin.so". Fix nve/2d
   derives from fix nve, whose header such builds may not ship (the PyPI
   wheel does not); the deck then uses fix nve, which gives the same bits
   (decks/impact_2d.lmp). See potentials/README.md.
------------------------------------------------------------------------- */

#include "compute_motion_2d.h"
#include "lammpsplugin.h"

// The wheel's headers carry no version.h; the build passes the version instead.
#ifndef LAMMPS_VERSION
#include "version.h"
#endif

using namespace LAMMPS_NS;

static Compute *motion_2d_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new ComputeMotion2d(lmp, narg, arg);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;

  plugin.version = LAMMPS_VERSION;
  plugin.style = "compute";
  plugin.name = "motion/2d";
  plugin.info = "Rigid-body motion of a group in 2-D (oblique-impact workflow)";
  plugin.author = "oblique-impact workflow";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &motion_2d_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);
}
