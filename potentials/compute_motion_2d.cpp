/* ----------------------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories

   This software is distributed under the GNU General Public License.
   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing author: the oblique-impact workflow (lattice disk on a
   lattice wall); see potentials/README.md.

   Compute motion/2d: the rigid-body motion of a group in a 2-D run, as a
   global vector of 9 values

     xcm ycm vxcm vycm Lz Izz omega_z fx fy

   the centre of mass, its velocity, the angular momentum and the moment
   of inertia about the centre of mass, omega_z = Lz / Izz, and the total
   force on the group. The same quantities as the group functions xcm(),
   vcm(), angmom(), inertia(), omega() and fcm() of equal-style variables,
   in two passes over the atoms instead of one or more per function: the
   impact deck writes them every few steps (docs/benchmarks/loop_floor.md).
   In 2-D the inertia tensor of a planar group has no xz, yz terms, so the
   z component of omega = I^-1 L is Lz / Izz.
------------------------------------------------------------------------- */

#include "compute_motion_2d.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "update.h"

#include <mpi.h>

using namespace LAMMPS_NS;

static constexpr int NVALUES = 9;

/* ---------------------------------------------------------------------- */

ComputeMotion2d::ComputeMotion2d(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), masstotal(0.0)
{
  if (narg != 3) error->all(FLERR, "Illegal compute motion/2d command: expects no arguments");
  if (domain->dimension != 2) error->all(FLERR, "Compute motion/2d requires dimension 2");

  vector_flag = 1;
  size_vector = NVALUES;
  extvector = 0;
  vector = new double[NVALUES];
}

/* ---------------------------------------------------------------------- */

ComputeMotion2d::~ComputeMotion2d()
{
  delete[] vector;
}

/* ---------------------------------------------------------------------- */

void ComputeMotion2d::init() {}

/* ---------------------------------------------------------------------- */

void ComputeMotion2d::compute_vector()
{
  invoked_vector = update->ntimestep;

  double **x = atom->x;
  double **v = atom->v;
  double **f = atom->f;
  int *mask = atom->mask;
  int *type = atom->type;
  imageint *image = atom->image;
  double *mass = atom->mass;
  double *rmass = atom->rmass;
  const int nlocal = atom->nlocal;

  // pass 1: mass, its first moments, momentum, force
  double one[7] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double unwrap[3];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double m = rmass ? rmass[i] : mass[type[i]];
    domain->unmap(x[i], image[i], unwrap);
    one[0] += m;
    one[1] += m * unwrap[0];
    one[2] += m * unwrap[1];
    one[3] += m * v[i][0];
    one[4] += m * v[i][1];
    one[5] += f[i][0];
    one[6] += f[i][1];
  }
  double all[7];
  MPI_Allreduce(one, all, 7, MPI_DOUBLE, MPI_SUM, world);
  masstotal = all[0];
  for (int k = 0; k < NVALUES; k++) vector[k] = 0.0;
  vector[7] = all[5];
  vector[8] = all[6];
  if (masstotal <= 0.0) return;
  const double xc = all[1] / masstotal, yc = all[2] / masstotal;

  // pass 2: angular momentum and moment of inertia about the centre of mass
  double two[2] = {0.0, 0.0};
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double m = rmass ? rmass[i] : mass[type[i]];
    domain->unmap(x[i], image[i], unwrap);
    const double dx = unwrap[0] - xc, dy = unwrap[1] - yc;
    two[0] += m * (dx * v[i][1] - dy * v[i][0]);
    two[1] += m * (dx * dx + dy * dy);
  }
  double sums[2];
  MPI_Allreduce(two, sums, 2, MPI_DOUBLE, MPI_SUM, world);

  vector[0] = xc;
  vector[1] = yc;
  vector[2] = all[3] / masstotal;
  vector[3] = all[4] / masstotal;
  vector[4] = sums[0];
  vector[5] = sums[1];
  vector[6] = sums[1] > 0.0 ? sums[0] / sums[1] : 0.0;
}
