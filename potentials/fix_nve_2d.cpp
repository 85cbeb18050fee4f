/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.

   Fix nve/2d: fix nve's velocity Verlet for a 2-D run, bit for bit: the
   same updates of x, y, vx, vy in the same order, with dtf / mass taken
   once per atom type instead of once per atom (the same quotient), and no
   z. Everything else (init, the time step, rRESPA) is fix nve's own. On
   the impact deck's scene fix nve was a quarter of the loop
   (docs/benchmarks/loop_floor.md).
------------------------------------------------------------------------- */

#include "fix_nve_2d.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "memory.h"

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

FixNVE2d::FixNVE2d(LAMMPS *lmp, int narg, char **arg) :
    FixNVE(lmp, narg, arg), dtfm_type(nullptr), ntypes(0)
{
  if (domain->dimension != 2) error->all(FLERR, "Fix nve/2d requires dimension 2");
}

/* ---------------------------------------------------------------------- */

FixNVE2d::~FixNVE2d()
{
  memory->destroy(dtfm_type);
}

/* ----------------------------------------------------------------------
   dtf / mass per type, for runs with per-type masses
------------------------------------------------------------------------- */

void FixNVE2d::set_dtfm()
{
  if (atom->ntypes != ntypes) {
    ntypes = atom->ntypes;
    memory->destroy(dtfm_type);
    memory->create(dtfm_type, ntypes + 1, "nve/2d:dtfm_type");
  }
  for (int t = 1; t <= ntypes; t++) dtfm_type[t] = dtf / atom->mass[t];
}

/* ---------------------------------------------------------------------- */

void FixNVE2d::initial_integrate(int /*vflag*/)
{
  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;

  if (rmass) {
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        const double dtfm = dtf / rmass[i];
        v[i][0] += dtfm * f[i][0];
        v[i][1] += dtfm * f[i][1];
        x[i][0] += dtv * v[i][0];
        x[i][1] += dtv * v[i][1];
      }
  } else {
    set_dtfm();
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        const double dtfm = dtfm_type[type[i]];
        v[i][0] += dtfm * f[i][0];
        v[i][1] += dtfm * f[i][1];
        x[i][0] += dtv * v[i][0];
        x[i][1] += dtv * v[i][1];
      }
  }
}

/* ---------------------------------------------------------------------- */

void FixNVE2d::final_integrate()
{
  double **v = atom->v;
  double **f = atom->f;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int *mask = atom->mask;
  int nlocal = atom->nlocal;
  if (igroup == atom->firstgroup) nlocal = atom->nfirst;

  if (rmass) {
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        const double dtfm = dtf / rmass[i];
        v[i][0] += dtfm * f[i][0];
        v[i][1] += dtfm * f[i][1];
      }
  } else {
    set_dtfm();
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) {
        const double dtfm = dtfm_type[type[i]];
        v[i][0] += dtfm * f[i][0];
        v[i][1] += dtfm * f[i][1];
      }
  }
}
