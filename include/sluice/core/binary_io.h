#pragma once
// Raw little-endian records for checkpoints: a writer that appends numbers and
// arrays to a buffer, and a reader that refuses to read past the end of what a
// file holds (a truncated checkpoint is then a clear error, not garbage).
// Every file starts with a tag and ends with a trailer that repeats its
// length, so a file cut short or padded is recognised before anything is used.

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace sluice
{
  class BinaryWriter
  {
  public:
    explicit BinaryWriter(const std::string &tag) { write_text(tag); }

    template <typename T>
    void write(const T &value)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      const char *p = reinterpret_cast<const char *>(&value);
      bytes.insert(bytes.end(), p, p + sizeof(T));
    }

    template <typename T>
    void write_vector(const std::vector<T> &v)
    {
      static_assert(std::is_trivially_copyable_v<T>);
      write<std::uint64_t>(v.size());
      const char *p = reinterpret_cast<const char *>(v.data());
      bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
    }

    void write_text(const std::string &s)
    {
      write<std::uint64_t>(s.size());
      bytes.insert(bytes.end(), s.begin(), s.end());
    }

    /// The bytes with the trailer (the length of what precedes it).
    std::string finish()
    {
      write<std::uint64_t>(bytes.size());
      return std::string(bytes.begin(), bytes.end());
    }

  private:
    std::vector<char> bytes;
  };

  /// Thrown for a file that ends early, has the wrong tag or a bad trailer.
  class BinaryFormatError : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  class BinaryReader
  {
  public:
    /// Checks the trailer and the tag.
    BinaryReader(std::string content, const std::string &tag) : data(std::move(content))
    {
      std::uint64_t length = 0;
      if (data.size() < sizeof(length))
        throw BinaryFormatError("the file is empty or cut short");
      std::memcpy(&length, data.data() + data.size() - sizeof(length), sizeof(length));
      if (length != data.size() - sizeof(length))
        throw BinaryFormatError("the file is cut short or damaged (its trailer does not match "
                                "its length)");
      end = length;
      if (read_text() != tag)
        throw BinaryFormatError("the file is not a '" + tag + "' file");
    }

    template <typename T>
    T read()
    {
      T value;
      take(&value, sizeof(T));
      return value;
    }

    template <typename T>
    std::vector<T> read_vector()
    {
      const std::uint64_t n = read<std::uint64_t>();
      if (n > (end - position) / sizeof(T))
        throw BinaryFormatError("the file is cut short");
      std::vector<T> v(n);
      take(v.data(), n * sizeof(T));
      return v;
    }

    std::string read_text()
    {
      const std::uint64_t n = read<std::uint64_t>();
      if (n > end - position)
        throw BinaryFormatError("the file is cut short");
      std::string s(data.data() + position, n);
      position += n;
      return s;
    }

    bool at_end() const { return position == end; }

  private:
    void take(void *target, const std::size_t n)
    {
      if (n > end - position)
        throw BinaryFormatError("the file is cut short");
      std::memcpy(target, data.data() + position, n);
      position += n;
    }

    std::string data;
    std::size_t position = 0, end = 0;
  };
} // namespace sluice
