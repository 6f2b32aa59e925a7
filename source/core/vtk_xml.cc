// VTK XML files: tags and DataArray payloads (see the header).

#include <sluice/core/scene_parameters.h>
#include <sluice/core/vtk_xml.h>

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <sstream>

namespace sluice
{
  namespace
  {
    bool is_space(const char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

    /// The size in bytes of one value of a VTK type, or 0 for a type not known.
    std::size_t size_of_type(const std::string &type)
    {
      static const std::map<std::string, std::size_t> sizes = {
        {"Int8", 1},  {"UInt8", 1},  {"Int16", 2},   {"UInt16", 2},  {"Int32", 4},
        {"UInt32", 4}, {"Int64", 8}, {"UInt64", 8},  {"Float32", 4}, {"Float64", 8}};
      const auto it = sizes.find(type);
      return it == sizes.end() ? 0 : it->second;
    }

    /// One value of 'type' at p, in the file's byte order.
    double value_at(const char *p, const std::string &type, const bool swap)
    {
      char        b[8];
      std::size_t n = size_of_type(type);
      std::memcpy(b, p, n);
      if (swap)
        std::reverse(b, b + n);
      // Templated decoding would hide the one-to-one list of VTK's types.
      if (type == "Float64") { double v; std::memcpy(&v, b, 8); return v; }
      if (type == "Float32") { float v; std::memcpy(&v, b, 4); return v; }
      if (type == "Int8") { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      if (type == "UInt8") { std::uint8_t v; std::memcpy(&v, b, 1); return v; }
      if (type == "Int16") { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      if (type == "UInt16") { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      if (type == "Int32") { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      if (type == "UInt32") { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      if (type == "Int64") { std::int64_t v; std::memcpy(&v, b, 8); return static_cast<double>(v); }
      std::uint64_t v;
      std::memcpy(&v, b, 8);
      return static_cast<double>(v);
    }
  } // namespace

  std::string XmlTag::attribute(const std::string &key, const std::string &fallback) const
  {
    const auto it = attributes.find(key);
    return it == attributes.end() ? fallback : it->second;
  }

  std::string decode_base64(const std::string &text)
  {
    static const std::string alphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string  bytes;
    unsigned int quantum = 0, n_bits = 0;
    bytes.reserve(text.size() / 4 * 3);
    for (const char c : text)
      {
        if (c == '=')
          {
            // The end of one encoded block: the next starts on a fresh quantum.
            quantum = n_bits = 0;
            continue;
          }
        const std::size_t v = alphabet.find(c);
        if (v == std::string::npos)
          continue; // whitespace between blocks
        quantum = (quantum << 6) | static_cast<unsigned int>(v);
        n_bits += 6;
        if (n_bits >= 8)
          {
            n_bits -= 8;
            bytes.push_back(static_cast<char>((quantum >> n_bits) & 0xff));
          }
      }
    return bytes;
  }

  VtkXmlFile::VtkXmlFile(const std::string &file_name)
    : name(file_name)
  {
    std::ifstream in(file_name, std::ios::binary);
    if (!in)
      fail("cannot be opened");
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    std::vector<std::size_t> open;
    std::size_t              pos = 0;
    while ((pos = bytes.find('<', pos)) != std::string::npos)
      {
        if (bytes.compare(pos, 4, "<!--") == 0)
          {
            pos = bytes.find("-->", pos);
            continue;
          }
        if (bytes[pos + 1] == '?')
          {
            pos = bytes.find("?>", pos);
            continue;
          }
        const std::size_t end = bytes.find('>', pos);
        if (end == std::string::npos)
          fail("has a tag that does not end (byte " + std::to_string(pos) + ")");
        if (bytes[pos + 1] == '/')
          {
            const std::string closing = bytes.substr(pos + 2, end - pos - 2);
            if (open.empty() || tag_list[open.back()].name != closing)
              fail("has an end tag </" + closing + "> that closes nothing");
            tag_list[open.back()].content_end = pos;
            open.pop_back();
            pos = end + 1;
            continue;
          }
        XmlTag            tag;
        const bool        empty = bytes[end - 1] == '/';
        std::istringstream text(bytes.substr(pos + 1, end - pos - (empty ? 2 : 1)));
        text >> tag.name;
        // Attributes: key="value" (or 'value'), separated by whitespace.
        std::string rest((std::istreambuf_iterator<char>(text)), std::istreambuf_iterator<char>());
        for (std::size_t i = 0; i < rest.size();)
          {
            const std::size_t eq = rest.find('=', i);
            if (eq == std::string::npos)
              break;
            std::string key = rest.substr(i, eq - i);
            key.erase(std::remove_if(key.begin(), key.end(), is_space), key.end());
            const std::size_t q = rest.find_first_of("\"'", eq);
            const std::size_t q_end = q == std::string::npos ? q : rest.find(rest[q], q + 1);
            if (q_end == std::string::npos)
              fail("has a tag <" + tag.name + "> with a bad attribute '" + key + "'");
            tag.attributes[key] = rest.substr(q + 1, q_end - q - 1);
            i = q_end + 1;
          }
        tag.content_begin = tag.content_end = end + 1;
        tag_list.push_back(tag);
        if (!empty)
          open.push_back(tag_list.size() - 1);
        pos = end + 1;
        if (tag.name == "AppendedData")
          {
            appended_encoding = tag.attribute("encoding", "raw");
            const std::size_t underscore = bytes.find('_', pos);
            if (underscore == std::string::npos)
              fail("has an <AppendedData> section without its '_' marker");
            appended_begin = underscore + 1;
            if (appended_encoding == "raw")
              break; // binary from here on
          }
      }
    if (tag_list.empty() || tag_list.front().name != "VTKFile")
      fail("is not a VTK XML file (no <VTKFile> root tag)");
  }

  void VtkXmlFile::fail(const std::string &what) const
  {
    throw InputError("error: the VTK file '" + name + "' " + what);
  }

  std::string VtkXmlFile::content(const XmlTag &tag) const
  {
    return bytes.substr(tag.content_begin, tag.content_end - tag.content_begin);
  }

  std::string VtkXmlFile::unpack(const std::string &stored, const std::string &array) const
  {
    const bool        wide     = root().attribute("header_type", "UInt32") == "UInt64";
    const bool        swap     = root().attribute("byte_order", "LittleEndian") == "BigEndian";
    const std::string word     = wide ? "UInt64" : "UInt32";
    const std::size_t h        = wide ? 8 : 4;
    const auto        header   = [&](const std::size_t k) -> std::size_t {
      if (stored.size() < (k + 1) * h)
        fail("has an array '" + array + "' whose data end early");
      return static_cast<std::size_t>(value_at(stored.data() + k * h, word, swap));
    };
    const std::string compressor = root().attribute("compressor");
    if (compressor.empty())
      {
        const std::size_t n = header(0);
        if (stored.size() < h + n)
          fail("has an array '" + array + "' whose data end early");
        return stored.substr(h, n);
      }
    if (compressor != "vtkZLibDataCompressor")
      fail("is compressed with '" + compressor +
           "'; Sluice reads zlib-compressed or uncompressed files (ParaView: Save Data, "
           "Compressor Type ZLib or None)");
    // Header: number of blocks, block size, size of the last block (0: full),
    // then each block's compressed size (VTK's vtkZLibDataCompressor).
    const std::size_t n_blocks = header(0), block = header(1), last = header(2);
    std::string       data;
    std::size_t       at = (3 + n_blocks) * h;
    for (std::size_t b = 0; b < n_blocks; ++b)
      {
        const std::size_t compressed = header(3 + b);
        uLongf            size = (b + 1 == n_blocks && last > 0) ? last : block;
        if (stored.size() < at + compressed)
          fail("has an array '" + array + "' whose compressed data end early");
        const std::size_t start = data.size();
        data.resize(start + size);
        if (uncompress(reinterpret_cast<Bytef *>(&data[start]), &size,
                       reinterpret_cast<const Bytef *>(stored.data() + at), compressed) != Z_OK)
          fail("has an array '" + array + "' whose zlib block " + std::to_string(b + 1) +
               " does not decompress");
        data.resize(start + size);
        at += compressed;
      }
    return data;
  }

  std::string VtkXmlFile::payload(const XmlTag &tag, const std::string &format) const
  {
    const std::string array = tag.attribute("Name", "(unnamed)");
    if (format == "binary")
      return unpack(decode_base64(content(tag)), array);
    if (appended_begin == std::string::npos)
      fail("has an appended array '" + array + "' but no <AppendedData> section");
    const std::size_t offset = std::stoull(tag.attribute("offset", "0"));
    if (appended_begin + offset > bytes.size())
      fail("has an array '" + array + "' whose offset lies beyond the file's end");
    if (appended_encoding == "base64")
      {
        const std::size_t end = bytes.find('<', appended_begin + offset);
        return unpack(decode_base64(bytes.substr(appended_begin + offset,
                                                 end - appended_begin - offset)),
                      array);
      }
    return unpack(bytes.substr(appended_begin + offset), array);
  }

  std::vector<double> VtkXmlFile::data_array(const XmlTag &tag, const std::size_t expected) const
  {
    const std::string array  = tag.attribute("Name", "(unnamed)");
    const std::string type   = tag.attribute("type");
    const std::string format = tag.attribute("format", "ascii");
    if (size_of_type(type) == 0)
      fail("has an array '" + array + "' of type '" + type + "', not a VTK number type");
    std::vector<double> values;
    if (format == "ascii")
      {
        std::istringstream in(content(tag));
        values.reserve(expected == any_size ? 0 : expected);
        double v;
        while (in >> v)
          values.push_back(v);
      }
    else if (format == "binary" || format == "appended")
      {
        const std::string raw  = payload(tag, format);
        const std::size_t size = size_of_type(type);
        const bool swap = root().attribute("byte_order", "LittleEndian") == "BigEndian";
        values.resize(raw.size() / size);
        for (std::size_t i = 0; i < values.size(); ++i)
          values[i] = value_at(raw.data() + i * size, type, swap);
      }
    else
      fail("has an array '" + array + "' in the unknown format '" + format + "'");
    if (expected != any_size && values.size() != expected)
      fail("has an array '" + array + "' with " + std::to_string(values.size()) +
           " values where " + std::to_string(expected) + " belong");
    return values;
  }
} // namespace sluice
