// Checkpoint and restart of the DEM (see the header for the layout).

#include <sluice/core/binary_io.h>
#include <sluice/core/names.h>
#include <sluice/core/output_files.h>
#include <sluice/core/scene_records.h>
#include <sluice/dem/dem_checkpoint.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace sluice
{
  namespace fs = std::filesystem;

  namespace
  {
    const std::string state_header    = "sluice dem checkpoint 1";
    const std::string particles_tag   = "sluice dem particles 1";
    const std::string rank_tag        = "sluice dem rank 1";
    const std::string checkpoint_infix = "-checkpoint-";

    std::string exact(const double v) { return exact_text(v); }

    std::string vec_text(const Vec3 &v)
    {
      return exact(v.x) + " " + exact(v.y) + " " + exact(v.z);
    }

    std::string pairs_text(const std::vector<PairOverride> &pairs)
    {
      std::string s;
      for (const auto &o : pairs)
        s += " " + std::to_string(o.type_a) + "-" + std::to_string(o.type_b) + ":" + exact(o.value);
      return s;
    }

    /// The scene entries a checkpoint depends on, one 'name = value' each.
    std::vector<std::string> signature(const DemSystem &dem)
    {
      const SceneParameters   &p = dem.p;
      std::vector<std::string> s;
      const auto line = [&](const std::string &name, const std::string &value) {
        s.push_back(name + " = " + value);
      };
      line("particles inserted", std::to_string(dem.n_inserted));
      line("material types", std::to_string(p.n_materials()));
      for (unsigned int m = 0; m < p.n_materials(); ++m)
        line("material " + std::to_string(m) + " density, young modulus, poisson ratio",
             exact(p.density[m]) + ", " + exact(p.young_modulus[m]) + ", " +
               exact(p.poisson_ratio[m]));
      line("contact/model", name_of(p.normal_model));
      line("contact/restitution", exact(p.restitution) + pairs_text(p.restitution_pairs));
      line("contact/friction", exact(p.friction) + pairs_text(p.friction_pairs));
      line("contact/rolling friction",
           exact(p.rolling_friction) + pairs_text(p.rolling_friction_pairs) + " model " +
             name_of(p.rolling_model));
      line("domain", vec_text(p.lower_corner) + " to " + vec_text(p.upper_corner) + " periodic " +
                       std::to_string(p.periodic[0]) + std::to_string(p.periodic[1]) +
                       std::to_string(p.periodic[2]));
      std::string walls;
      for (unsigned int w = 0; w < dem.walls.n_walls(); ++w)
        walls += " " + dem.walls.name(w) + ":" + std::to_string(dem.walls.material(w));
      line("walls", std::to_string(dem.walls.n_walls()) + walls);
      line("time step", exact(dem.dt));
      line("particle fields", dem.fields.signature());
      if (dem.clumps)
        {
          // The bodies' shapes: their mass properties follow from these.
          std::string shapes;
          for (const ClumpTemplate &t : dem.clumps->templates)
            {
              shapes += " " + t.name + ":";
              for (std::size_t k = 0; k < t.radii.size(); ++k)
                shapes += (k ? "," : "") + vec_text(t.members[k]) + "/" + exact(t.radii[k]);
            }
          line("clump templates", std::to_string(dem.clumps->templates.size()) + shapes);
        }
      return s;
    }

    /// Rank 0 receives every rank's bytes, in rank order.
    std::vector<std::string> gather_to_root(const std::string &mine, MPI_Comm comm)
    {
      int rank, n_ranks;
      MPI_Comm_rank(comm, &rank);
      MPI_Comm_size(comm, &n_ranks);
      int              size = static_cast<int>(mine.size());
      std::vector<int> sizes(n_ranks), offsets(n_ranks, 0);
      MPI_Gather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, 0, comm);
      std::string all;
      if (rank == 0)
        {
          std::partial_sum(sizes.begin(), sizes.end() - 1, offsets.begin() + 1);
          all.resize(offsets.back() + sizes.back());
        }
      MPI_Gatherv(mine.data(), size, MPI_CHAR, all.data(), sizes.data(), offsets.data(),
                  MPI_CHAR, 0, comm);
      std::vector<std::string> parts;
      if (rank == 0)
        for (int r = 0; r < n_ranks; ++r)
          parts.push_back(all.substr(offsets[r], sizes[r]));
      return parts;
    }

    void write_binary(const std::string &path, const std::string &bytes)
    {
      std::ofstream out(path, std::ios::binary);
      out.write(bytes.data(), bytes.size());
      out.close();
      check_stream(out, path);
    }

    std::string read_whole(const std::string &path)
    {
      std::ifstream in(path, std::ios::binary);
      if (!in)
        return {};
      return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }

    /// Every particle and tangential history, as particles.bin holds them.
    struct ParticleTable
    {
      std::vector<std::uint64_t> id;
      std::vector<Vec3>          x, v, w, f, t;
      std::vector<double>        radius;
      std::vector<unsigned int>  type;
      std::vector<double>        extra;
      std::vector<std::uint64_t> history_first, history_second;
      std::vector<std::uint8_t>  history_wall;
      std::vector<Vec3>          history;

      void write(BinaryWriter &out) const
      {
        out.write_vector(id);
        for (const auto *a : {&x, &v, &w, &f, &t})
          out.write_vector(*a);
        out.write_vector(radius);
        out.write_vector(type);
        out.write_vector(extra);
        out.write_vector(history_first);
        out.write_vector(history_second);
        out.write_vector(history_wall);
        out.write_vector(history);
      }
      void read(BinaryReader &in)
      {
        id = in.read_vector<std::uint64_t>();
        for (auto *a : {&x, &v, &w, &f, &t})
          *a = in.read_vector<Vec3>();
        radius         = in.read_vector<double>();
        type           = in.read_vector<unsigned int>();
        extra          = in.read_vector<double>();
        history_first  = in.read_vector<std::uint64_t>();
        history_second = in.read_vector<std::uint64_t>();
        history_wall   = in.read_vector<std::uint8_t>();
        history        = in.read_vector<Vec3>();
        for (const auto *a : {&x, &v, &w, &f, &t})
          if (a->size() != id.size())
            throw BinaryFormatError("its particle arrays differ in length");
        if (radius.size() != id.size() || type.size() != id.size())
          throw BinaryFormatError("its particle arrays differ in length");
        if (history_second.size() != history_first.size() ||
            history_wall.size() != history_first.size() || history.size() != history_first.size())
          throw BinaryFormatError("its history arrays differ in length");
      }
      void append(const ParticleTable &o)
      {
        id.insert(id.end(), o.id.begin(), o.id.end());
        for (auto [a, b] : {std::pair{&x, &o.x}, {&v, &o.v}, {&w, &o.w}, {&f, &o.f}, {&t, &o.t}})
          a->insert(a->end(), b->begin(), b->end());
        radius.insert(radius.end(), o.radius.begin(), o.radius.end());
        type.insert(type.end(), o.type.begin(), o.type.end());
        extra.insert(extra.end(), o.extra.begin(), o.extra.end());
        history_first.insert(history_first.end(), o.history_first.begin(), o.history_first.end());
        history_second.insert(history_second.end(), o.history_second.begin(),
                              o.history_second.end());
        history_wall.insert(history_wall.end(), o.history_wall.begin(), o.history_wall.end());
        history.insert(history.end(), o.history.begin(), o.history.end());
      }
    };

    ParticleTable local_table(const DemSystem &dem)
    {
      // The handler's particles: the bodies in a clump scene.
      const ParticleStorage &P = dem.handler_particles();
      ParticleTable          table;
      table.id.assign(P.id.begin(), P.id.begin() + P.n_local);
      table.x.assign(P.position.begin(), P.position.begin() + P.n_local);
      table.v.assign(P.velocity.begin(), P.velocity.begin() + P.n_local);
      table.w.assign(P.angular_velocity.begin(), P.angular_velocity.begin() + P.n_local);
      table.f.assign(P.force.begin(), P.force.begin() + P.n_local);
      table.t.assign(P.torque.begin(), P.torque.begin() + P.n_local);
      table.radius.assign(P.radius.begin(), P.radius.begin() + P.n_local);
      table.type.assign(P.type.begin(), P.type.begin() + P.n_local);
      table.extra.assign(P.extra.begin(), P.extra.begin() + P.n_extra * P.n_local);
      ContactHistoryMap histories;
      dem.list.collect_histories(dem.particles, histories);
      for (const auto &[key, h] : histories)
        {
          table.history_first.push_back(key.first);
          table.history_second.push_back(key.second);
          table.history_wall.push_back(key.wall);
          table.history.push_back(h);
        }
      return table;
    }

    /// The local arrays' order and the neighbour list, for a restart on as
    /// many ranks.
    std::string rank_file(const DemSystem &dem)
    {
      const NeighbourList &L = dem.list;
      BinaryWriter         out(rank_tag);
      out.write<std::uint32_t>(dem.n_ranks);
      out.write_vector(dem.particles.id);
      out.write<std::uint32_t>(dem.particles.n_local);
      out.write_vector(L.offset);
      out.write_vector(L.partner);
      out.write_vector(L.history);
      out.write_vector(L.wall_offset);
      out.write_vector(L.wall_partner);
      out.write_vector(L.wall_history);
      out.write_vector(L.position_at_build);
      out.write_vector(dem.particles.coordination);
      out.write<std::uint32_t>(L.n_builds);
      out.write(dem.stats);
      out.write_vector(dem.wall_forces);
      if (dem.walls.n_meshes() > 0)
        {
          out.write_vector(L.mesh_offset);
          out.write_vector(L.mesh_candidate);
          out.write_vector(L.mesh_contact_offset);
          out.write_vector(L.mesh_contact);
          out.write_vector(dem.mesh_loads.torque);
          out.write_vector(dem.mesh_loads.power);
        }
      return out.finish();
    }
  } // namespace

  void prune_checkpoints(const std::string &newest, const unsigned int keep)
  {
    const fs::path    dir    = fs::path(newest).parent_path();
    const std::string name   = fs::path(newest).filename().string();
    const std::string prefix = name.substr(0, name.size() - 10);
    std::vector<std::string> found;
    for (const auto &entry : fs::directory_iterator(dir))
      {
        const std::string f = entry.path().filename().string();
        if (f.size() == name.size() && f.compare(0, prefix.size(), prefix) == 0 &&
            f.find_first_not_of("0123456789", prefix.size()) == std::string::npos)
          found.push_back(f);
      }
    std::sort(found.begin(), found.end());
    for (std::size_t k = 0; k + keep < found.size(); ++k)
      fs::remove_all(dir / found[k]);
  }

  CheckpointSchedule::CheckpointSchedule(const SceneParameters &p, const double time)
    : step_interval(p.checkpoint_step_interval), time_interval(p.checkpoint_time_interval)
  {
    if (time_interval > 0.)
      next_time = time_interval * (std::floor(time / time_interval + 1e-9) + 1.);
  }

  bool CheckpointSchedule::due(const unsigned long long step, const double time, const double dt)
  {
    if (step_interval > 0)
      return step % step_interval == 0;
    if (time_interval > 0. && time >= next_time - 0.5 * dt)
      {
        next_time += time_interval;
        return true;
      }
    return false;
  }

  std::string checkpoint_path(const std::string &directory, const std::string &base,
                              const unsigned long long step)
  {
    char digits[32];
    std::snprintf(digits, sizeof(digits), "%010llu", step);
    return directory + "/" + base + checkpoint_infix + digits;
  }

  void save_dem_checkpoint(const DemSystem &dem, const std::string &path,
                           const std::vector<std::string> &scene_records, const unsigned int keep,
                           const CheckpointAddition &addition)
  {
    const std::string tmp  = path + ".writing";
    const bool        root = dem.rank == 0;
    // The directory and its files (an interrupted earlier attempt is replaced).
    int ok = 1;
    if (root)
      {
        std::error_code error;
        fs::remove_all(tmp, error);
        ok = fs::create_directories(tmp, error) && !error;
      }
    MPI_Bcast(&ok, 1, MPI_INT, 0, dem.comm);
    if (!ok)
      throw OutputError("sluice: cannot create the checkpoint directory '" + tmp + "'");

    dem.exchange->save(tmp + "/mesh");
    write_binary(tmp + "/rank-" + std::to_string(dem.rank) + ".bin", rank_file(dem));
    const std::vector<int> owners = dem.exchange->cell_owners();
    if (addition.write)
      addition.write(tmp);

    BinaryWriter local(particles_tag);
    local_table(dem).write(local);
    const std::vector<std::string> parts = gather_to_root(local.finish(), dem.comm);
    double max_overlap = dem.stats.max_overlap_ratio;
    MPI_Allreduce(MPI_IN_PLACE, &max_overlap, 1, MPI_DOUBLE, MPI_MAX, dem.comm);
    // The observer's sums over all ranks (restored on rank 0).
    std::vector<double> observed;
    if (dem.observer())
      {
        observed = dem.observer()->state();
        MPI_Allreduce(MPI_IN_PLACE, observed.data(), observed.size(), MPI_DOUBLE, MPI_SUM,
                      dem.comm);
      }
    if (root)
      {
        ParticleTable all;
        for (const std::string &part : parts)
          {
            BinaryReader  in(part, particles_tag);
            ParticleTable t;
            t.read(in);
            all.append(t);
          }
        BinaryWriter out(particles_tag);
        all.write(out);
        write_binary(tmp + "/particles.bin", out.finish());

        // The state last: its 'end' line marks a complete checkpoint.
        std::ostringstream state;
        state << state_header << "\n";
        for (const std::string &s : signature(dem))
          state << "signature " << s << "\n";
        for (const std::string &s : addition.signature)
          state << "signature " << s << "\n";
        state << "ranks " << dem.n_ranks << "\nstep " << dem.step << "\ninserted "
              << dem.n_inserted << "\nlost " << dem.n_lost << "\nstream " << dem.n_added << " "
              << dem.n_removed << "\nmax_overlap_ratio "
              << exact(max_overlap) << "\nexchange";
        for (const unsigned int c : dem.exchange->counters())
          state << " " << c;
        state << "\nowners";
        for (const int o : owners)
          state << " " << o;
        state << "\nwalls";
        for (const double v : dem.walls.state())
          state << " " << exact(v);
        state << "\n";
        if (dem.observer())
          {
            state << "observer";
            for (const double v : observed)
              state << " " << exact(v);
            state << "\n";
          }
        // Every file but the per-rank ones and the particles (which carry
        // their own length) is listed with its size.
        for (const auto &entry : fs::directory_iterator(tmp))
          if (const std::string name = entry.path().filename().string();
              name.compare(0, 5, "rank-") != 0 && name != "particles.bin")
            state << "file " << entry.path().filename().string() << " "
                  << fs::file_size(entry.path()) << "\n";
        for (const std::string &r : scene_records)
          state << "scene " << r << "\n";
        state << "end\n";
        write_binary(tmp + "/state", state.str());
      }
    MPI_Barrier(dem.comm);
    ok = 1;
    if (root)
      {
        std::error_code error;
        fs::remove_all(path, error);
        fs::rename(tmp, path, error);
        ok = !error;
        if (ok)
          prune_checkpoints(path, keep);
      }
    MPI_Bcast(&ok, 1, MPI_INT, 0, dem.comm);
    if (!ok)
      throw OutputError("sluice: cannot rename the checkpoint '" + tmp + "' to '" + path + "'");
  }

  std::string find_checkpoint(const std::string &restart_from, const std::string &directory,
                              const std::string &base, const std::string &file_name)
  {
    const std::string where = "error in '" + file_name + "': entry 'checkpoint/restart from' = '" +
                              restart_from + "': ";
    if (restart_from != "latest")
      {
        if (!fs::is_directory(restart_from))
          throw InputError(where + "no such checkpoint directory");
        return restart_from;
      }
    std::string newest;
    if (fs::is_directory(directory))
      for (const auto &entry : fs::directory_iterator(directory))
        {
          const std::string f = entry.path().filename().string();
          const std::string prefix = base + checkpoint_infix;
          if (f.size() == prefix.size() + 10 && f.compare(0, prefix.size(), prefix) == 0 &&
              fs::exists(entry.path() / "state") && f > newest)
            newest = f;
        }
    if (newest.empty())
      throw InputError(where + "there is no complete checkpoint '" + base + checkpoint_infix +
                       "*' in '" + directory + "'");
    return directory + "/" + newest;
  }

  std::vector<std::string> load_dem_checkpoint(DemSystem &dem, const std::string &path,
                                               const std::vector<std::string> &scene_signature)
  {
    const std::string where = "error in '" + dem.p.file_name +
                              "': entry 'checkpoint/restart from': checkpoint '" + path + "': ";
    const auto fail = [&](const std::string &what) { throw InputError(where + what); };

    // ---- Everything is read and checked before the DEM changes ----
    std::vector<std::string> lines;
    {
      std::istringstream in(read_whole(path + "/state"));
      for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    }
    if (lines.empty())
      fail("'state' is missing or empty: not a complete checkpoint");
    if (lines[0] != state_header)
      fail("'state' is not a Sluice DEM checkpoint (it starts with '" + lines[0].substr(0, 60) +
           "')");
    if (lines.back() != "end")
      fail("'state' is cut short (no 'end' line)");

    std::vector<std::string> expected = signature(dem);
    expected.insert(expected.end(), scene_signature.begin(), scene_signature.end());
    std::vector<std::string> found, scene_records;
    unsigned int                   saved_ranks = 0;
    std::vector<unsigned int>      counters;
    std::vector<double>            wall_state, observed;
    bool                           has_observed = false;
    std::vector<int>               owners;
    double                         max_overlap = 0.;
    for (const std::string &line : lines)
      {
        std::istringstream in(line);
        std::string        key;
        in >> key;
        const std::string rest = line.size() > key.size() + 1 ? line.substr(key.size() + 1) : "";
        if (key == "signature")
          found.push_back(rest);
        else if (key == "scene")
          scene_records.push_back(rest);
        else if (key == "ranks")
          in >> saved_ranks;
        else if (key == "step")
          in >> dem.step;
        else if (key == "lost")
          in >> dem.n_lost;
        else if (key == "stream")
          in >> dem.n_added >> dem.n_removed;
        else if (key == "max_overlap_ratio")
          in >> max_overlap;
        else if (key == "exchange")
          for (unsigned int c; in >> c;)
            counters.push_back(c);
        else if (key == "owners")
          for (int o; in >> o;)
            owners.push_back(o);
        else if (key == "walls")
          for (double v; in >> v;)
            wall_state.push_back(v);
        else if (key == "observer")
          {
            has_observed = true;
            for (double v; in >> v;)
              observed.push_back(v);
          }
        else if (key == "file")
          {
            std::string   name;
            std::uintmax_t size = 0;
            in >> name >> size;
            std::error_code error;
            const std::uintmax_t actual = fs::file_size(path + "/" + name, error);
            if (error)
              fail("'" + name + "' is missing");
            if (actual != size)
              fail("'" + name + "' has " + std::to_string(actual) + " bytes, the checkpoint "
                   "wrote " + std::to_string(size) + ": it is cut short or damaged");
          }
      }
    for (std::size_t k = 0; k < std::max(found.size(), expected.size()); ++k)
      if (k >= found.size() || k >= expected.size() || found[k] != expected[k])
        fail("it was written by a different scene: the checkpoint has '" +
             (k < found.size() ? found[k] : std::string("nothing")) + "', this scene has '" +
             (k < expected.size() ? expected[k] : std::string("nothing")) + "'");
    if (counters.size() != 2 || wall_state.size() != dem.walls.state().size())
      fail("'state' is damaged (exchange counters or wall positions)");
    // A checkpoint written before its run began to observe has no sums: the
    // observer starts from zero, as that run's would have.
    if (dem.observer() && !has_observed)
      observed.assign(dem.observer()->state().size(), 0.);
    if (dem.observer() && observed.size() != dem.observer()->state().size())
      fail("'state' has contact-observer sums that do not fit this scene's walls and meshes");

    ParticleTable table;
    try
      {
        BinaryReader in(read_whole(path + "/particles.bin"), particles_tag);
        table.read(in);
        if (table.extra.size() != table.id.size() * dem.handler_particles().n_extra)
          throw BinaryFormatError("its coupling data do not fit its particles");
      }
    catch (const BinaryFormatError &e)
      {
        fail("'particles.bin': " + std::string(e.what()));
      }
    const unsigned long long held = dem.n_inserted + dem.n_added - dem.n_removed - dem.n_lost;
    if (table.id.size() != held)
      fail("'particles.bin' holds " + std::to_string(table.id.size()) + " particles, 'state' " +
           std::to_string(held));

    // The same number of ranks: this rank's arrays and list, as they were.
    const bool same_ranks = saved_ranks == static_cast<unsigned int>(dem.n_ranks);
    std::unique_ptr<BinaryReader> rank_in;
    if (same_ranks)
      try
        {
          const std::string name = "rank-" + std::to_string(dem.rank) + ".bin";
          rank_in = std::make_unique<BinaryReader>(read_whole(path + "/" + name), rank_tag);
        }
      catch (const BinaryFormatError &e)
        {
          fail("'rank-" + std::to_string(dem.rank) + ".bin': " + std::string(e.what()));
        }

    // ---- The particles back in their cells, on their ranks ----
    // On as many ranks: the saved cells, partition and particle order. On
    // another number: the particles inserted anew (the handler's layout
    // depends on the number of ranks).
    if (same_ranks)
      try
        {
          dem.exchange->load(path + "/mesh", owners);
        }
      catch (const std::exception &e)
        {
          fail("the mesh files cannot be read: " + std::string(e.what()).substr(0, 400));
        }
    else
      {
        std::vector<ParticleRecord> records(table.id.size());
        const unsigned int          n_extra = dem.handler_particles().n_extra;
        for (std::size_t k = 0; k < records.size(); ++k)
          {
            records[k].position         = table.x[k];
            records[k].radius           = table.radius[k];
            records[k].type             = table.type[k];
            records[k].velocity         = table.v[k];
            records[k].angular_velocity = table.w[k];
            if (dem.clumps)
              {
                // The body's shape and orientation travel with it as a record
                // (ghosts included); the rest of its fields follow below.
                const double *e = table.extra.data() + k * n_extra;
                const double *q = e + dem.fields.find(clump_fields::orientation)->offset;
                records[k].orientation    = {{q[0], q[1], q[2], q[3]}};
                records[k].clump_template = e[dem.fields.find(clump_fields::shape)->offset];
                records[k].clump_scale    = e[dem.fields.find(clump_fields::scale)->offset];
              }
          }
        dem.exchange->reinsert(records, table.id, dem.box);
      }
    dem.exchange->set_counters(counters);
    ParticleStorage &P = dem.handler_particles();
    dem.histories.clear();
    dem.exchange->fill_storage(P, dem.histories, dem.p.density);
    dem.histories.clear();
    std::unordered_map<std::uint64_t, std::size_t> row;
    row.reserve(table.id.size());
    for (std::size_t k = 0; k < table.id.size(); ++k)
      row[table.id[k]] = k;
    unsigned long long unknown = 0;
    for (unsigned int i = 0; i < P.n_local; ++i)
      {
        const auto it = row.find(P.id[i]);
        if (it == row.end())
          {
            ++unknown;
            continue;
          }
        const std::size_t k = it->second;
        P.position[i]         = table.x[k];
        P.velocity[i]         = table.v[k];
        P.angular_velocity[i] = table.w[k];
        P.force[i]            = table.f[k];
        P.torque[i]           = table.t[k];
        // The fields a checkpoint keeps; the others start at zero.
        std::fill(P.extra_of(i), P.extra_of(i) + P.n_extra, 0.);
        for (const ParticleField &f : dem.fields.fields())
          if (f.checkpoint)
            std::copy(table.extra.begin() + k * P.n_extra + f.offset,
                      table.extra.begin() + k * P.n_extra + f.offset + f.size,
                      P.extra_of(i) + f.offset);
      }
    MPI_Allreduce(MPI_IN_PLACE, &unknown, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, dem.comm);
    if (unknown > 0)
      fail(std::to_string(unknown) + " particles in the mesh files are not in 'particles.bin'");
    if (dem.n_ranks > 1)
      dem.exchange->update_ghosts(P);
    // A clump scene's members, from the bodies as restored.
    dem.refresh_members();
    ParticleStorage &members = dem.particles;
    dem.walls.set_state(wall_state);
    if (dem.observer())
      dem.observer()->set_state(dem.rank == 0 ? observed :
                                                std::vector<double>(observed.size(), 0.));

    // ---- The neighbour list: as it was, or built anew ----
    int exact_list = 0;
    if (same_ranks)
      {
        BinaryReader &in = *rank_in;
        in.read<std::uint32_t>();
        const auto         ids     = in.read_vector<std::uint64_t>();
        const unsigned int n_local = in.read<std::uint32_t>();
        NeighbourList     &L       = dem.list;
        L.offset                   = in.read_vector<unsigned int>();
        L.partner                  = in.read_vector<unsigned int>();
        L.history                  = in.read_vector<Vec3>();
        L.history_may_be_nonzero.clear();
        L.wall_offset              = in.read_vector<unsigned int>();
        L.wall_partner             = in.read_vector<unsigned int>();
        L.wall_history             = in.read_vector<Vec3>();
        L.position_at_build        = in.read_vector<Vec3>();
        const auto coordination    = in.read_vector<unsigned int>();
        L.n_builds                 = in.read<std::uint32_t>();
        dem.stats                  = in.read<ContactStatistics>();
        dem.wall_forces            = in.read_vector<Vec3>();
        if (dem.walls.n_meshes() > 0)
          {
            L.mesh_offset            = in.read_vector<unsigned int>();
            L.mesh_candidate         = in.read_vector<MeshTriangle>();
            L.mesh_contact_offset    = in.read_vector<unsigned int>();
            L.mesh_contact           = in.read_vector<MeshContactHistory>();
            dem.mesh_loads.torque    = in.read_vector<Vec3>();
            dem.mesh_loads.power     = in.read_vector<double>();
          }
        // The partners are array indices: valid if the arrays are in the saved
        // order (they are, unless the particles or ghosts came back in another order).
        exact_list = n_local == members.n_local && ids == members.id &&
                     coordination.size() == members.coordination.size();
        if (exact_list)
          members.coordination = coordination;
      }
    MPI_Allreduce(MPI_IN_PLACE, &exact_list, 1, MPI_INT, MPI_MIN, dem.comm);
    if (!exact_list)
      {
        for (std::size_t k = 0; k < table.history.size(); ++k)
          dem.histories[{table.history_first[k], table.history_second[k],
                         table.history_wall[k] != 0}] = table.history[k];
        dem.build_list();
        dem.histories.clear();
        dem.stats                   = ContactStatistics();
        dem.stats.max_overlap_ratio = max_overlap;
        std::fill(dem.wall_forces.begin(), dem.wall_forces.end(), Vec3());
        std::fill(dem.mesh_loads.torque.begin(), dem.mesh_loads.torque.end(), Vec3());
        std::fill(dem.mesh_loads.power.begin(), dem.mesh_loads.power.end(), 0.);
      }
    return scene_records;
  }
} // namespace sluice
