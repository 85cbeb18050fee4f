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
