#pragma once
// VTK XML data arrays in the binary inline encoding (base64 of a 32-bit byte
// count followed by the raw little-endian values), as the particle and mesh
// snapshots write them.

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace sluice
{
  namespace vtk
  {
    std::string base64(const std::vector<unsigned char> &bytes);

    template <typename T>
    std::string encode(const std::vector<T> &data)
    {
      const std::uint32_t        n = data.size() * sizeof(T);
      std::vector<unsigned char> bytes(sizeof(n) + n);
      const auto                *count = reinterpret_cast<const unsigned char *>(&n);
      std::copy(count, count + sizeof(n), bytes.begin());
      if (n > 0)
        {
          const auto *values = reinterpret_cast<const unsigned char *>(data.data());
          std::copy(values, values + n, bytes.begin() + sizeof(n));
        }
      return base64(bytes);
    }

    inline const char *type_name(double) { return "Float64"; }
    inline const char *type_name(std::int32_t) { return "Int32"; }
    inline const char *type_name(std::int64_t) { return "Int64"; }
    inline const char *type_name(std::uint8_t) { return "UInt8"; }

    /// One <DataArray> element.
    template <typename T>
    void data_array(std::ostream &out, const std::string &name, const unsigned int components,
                    const std::vector<T> &data)
    {
      out << "        <DataArray type=\"" << type_name(T()) << "\" Name=\"" << name
          << "\" NumberOfComponents=\"" << components << "\" format=\"binary\">\n          "
          << encode(data) << "\n        </DataArray>\n";
    }
  } // namespace vtk
} // namespace sluice
