/* ----------------------------------------------------------------------
   Run-time registration of pair style polyline/exp into a LAMMPS without
   the PLUGIN package (Debian's 29 Sep 2021 build): the creator goes into
   the instance's pair style map. Call it again after "clear", which
   rebuilds that map. See potentials/README.md.
------------------------------------------------------------------------- */

#include "force.h"
#include "lammps.h"
#include "pair_polyline_exp.h"

using namespace LAMMPS_NS;

static Pair *polyline_exp_creator(LAMMPS *lmp)
{
  return new PairPolylineExp(lmp);
}

extern "C" int polyline_exp_register(void *handle)
{
  auto lmp = static_cast<LAMMPS *>(handle);
  (*lmp->force->pair_map)["polyline/exp"] = &polyline_exp_creator;
  return 0;
}
