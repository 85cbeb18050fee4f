/* ----------------------------------------------------------------------
   Run-time registration of bond style harmonic/quartic into a LAMMPS
   without the PLUGIN package (Debian's 29 Sep 2021 build): the creator goes
   into the instance's bond style map. Call it again after "clear", which
   rebuilds that map. See potentials/README.md.
------------------------------------------------------------------------- */

#include "bond_harmonic_quartic.h"
#include "force.h"
#include "lammps.h"

using namespace LAMMPS_NS;

static Bond *harmonic_quartic_creator(LAMMPS *lmp)
{
  return new BondHarmonicQuartic(lmp);
}

extern "C" int harmonic_quartic_register(void *handle)
{
  auto lmp = static_cast<LAMMPS *>(handle);
  (*lmp->force->bond_map)["harmonic/quartic"] = &harmonic_quartic_creator;
  return 0;
}
