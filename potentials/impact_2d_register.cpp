/* ----------------------------------------------------------------------
   Run-time registration of the impact deck's 2-D styles, compute motion/2d
   and fix nve/2d, into a LAMMPS without the PLUGIN package (Debian's 29 Sep
   2021 build): the creators go into the instance's style maps. Call it
   again after "clear", which rebuilds those maps. See potentials/README.md.
------------------------------------------------------------------------- */

#include "compute_motion_2d.h"
#include "fix_nve_2d.h"
#include "lammps.h"
#include "modify.h"

using namespace LAMMPS_NS;

static Compute *motion_2d_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new ComputeMotion2d(lmp, narg, arg);
}

static Fix *nve_2d_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixNVE2d(lmp, narg, arg);
}

extern "C" int impact_2d_register(void *handle)
{
  auto lmp = static_cast<LAMMPS *>(handle);
  (*lmp->modify->compute_map)["motion/2d"] = &motion_2d_creator;
  (*lmp->modify->fix_map)["nve/2d"] = &nve_2d_creator;
  return 0;
}
