// The per-particle CSV dump (see the header).

#include <sluice/core/output_files.h>
#include <sluice/dem/particle_csv.h>

#include <algorithm>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <vector>

namespace sluice
{
  void write_rows_by_id(const std::vector<double> &mine, const int n_fields,
                        const int n_integer_fields, const std::string &header, const double time,
                        const std::string &path, MPI_Comm comm)
  {
    int rank, n_ranks;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &n_ranks);
    const int        n_mine = mine.size();
    std::vector<int> counts(n_ranks), offsets(n_ranks);
    MPI_Gather(&n_mine, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
    std::vector<double> all;
    if (rank == 0)
      {
        std::partial_sum(counts.begin(), counts.end() - 1, offsets.begin() + 1);
        all.resize(offsets.back() + counts.back());
      }
    MPI_Gatherv(mine.data(), n_mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                MPI_DOUBLE, 0, comm);
    if (rank != 0)
      return;

    const std::size_t        n = all.size() / n_fields;
    std::vector<std::size_t> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](const std::size_t a, const std::size_t b) {
      return all[n_fields * a] < all[n_fields * b];
    });
    std::ostringstream out;
    out << "# time = " << std::setprecision(10) << time << " s\n"
        << header << "\n"
        << std::setprecision(12);
    for (const std::size_t k : order)
      {
        const double *row = all.data() + n_fields * k;
        out << static_cast<unsigned long long>(row[0]);
        for (int f = 1; f < n_fields; ++f)
          if (f < n_integer_fields)
            out << ',' << static_cast<unsigned long long>(row[f]);
          else
            out << ',' << row[f];
        out << '\n';
      }
    write_file_atomically(path, out.str());
  }

  std::string particle_csv_path(const std::string &directory, const std::string &base_name,
                                const unsigned int index, const std::string &kind)
  {
    std::ostringstream path;
    path << directory << "/" << base_name << "_" << kind << "_" << std::setw(5)
         << std::setfill('0') << index << ".csv";
    return path.str();
  }

  void write_particle_csv(const ParticleStorage &P, const double time,
                          const std::string &directory, const std::string &base_name,
                          const unsigned int index, MPI_Comm comm)
  {
    constexpr int       n_fields = 15;
    std::vector<double> mine;
    mine.reserve(n_fields * P.n_local);
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        const Vec3 *vectors[4] = {&P.position[i], &P.velocity[i], &P.angular_velocity[i],
                                  &P.force[i]};
        mine.push_back(static_cast<double>(P.id[i]));
        mine.push_back(P.type[i]);
        mine.push_back(P.radius[i]);
        for (const Vec3 *v : vectors)
          for (unsigned int d = 0; d < 3; ++d)
            mine.push_back((*v)[d]);
      }
    write_rows_by_id(mine, n_fields, 2, "id,type,radius,x,y,z,vx,vy,vz,wx,wy,wz,fx,fy,fz", time,
                     particle_csv_path(directory, base_name, index), comm);
  }
} // namespace sluice
