/* ----------------------------------------------------------------------
   Run-time registration of angle style area/barrier and fix area/barrier
   into a LAMMPS without the PLUGIN package (Debian's 29 Sep 2021 build):
   the creators go into the instance's style maps. Call it again after
   "clear", which rebuilds those maps. See potentials/README.md.
------------------------------------------------------------------------- */

#include "angle_area_barrier.h"
#include "fix_area_barrier.h"
#include "force.h"
#include "lammps.h"
#include "modify.h"

using namespace LAMMPS_NS;

static Angle *area_barrier_creator(LAMMPS *lmp)
{
  return new AngleAreaBarrier(lmp);
}

static Fix *area_barrier_fix_creator(LAMMPS *lmp, int narg, char **arg)
{
  return new FixAreaBarrier(lmp, narg, arg);
}

extern "C" int area_barrier_register(void *handle)
{
  auto lmp = static_cast<LAMMPS *>(handle);
  (*lmp->force->angle_map)["area/barrier"] = &area_barrier_creator;
  (*lmp->modify->fix_map)["area/barrier"] = &area_barrier_fix_creator;
  return 0;
}
