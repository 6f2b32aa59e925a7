#pragma once
// The parts of VTK's XML file format (https://docs.vtk.org/en/latest/design_documents/
// VTKFileFormats.html) a reader of unstructured grids needs: the tags with
// their attributes, and the DataArray payloads in each encoding VTK and
// deal.II write: 'ascii', inline 'binary' (base64) and 'appended' (raw or
// base64), each optionally zlib-compressed in blocks (the 'compressor'
// attribute), with 32- or 64-bit headers ('header_type') in either byte order.
// Everything is returned as doubles. Errors throw InputError naming the file.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace sluice
{
  /// One start tag: its name, its attributes, and where its content lies in
  /// the file (from the end of the start tag to the matching end tag; empty
  /// for a tag closed with '/>').
  constexpr std::size_t any_size = static_cast<std::size_t>(-1);

  struct XmlTag
  {
    std::string                        name;
    std::map<std::string, std::string> attributes;
    std::size_t                        content_begin = 0, content_end = 0;

    /// The attribute, or 'fallback' when absent.
    std::string attribute(const std::string &key, const std::string &fallback = "") const;
  };

  /// A VTK XML file read into memory: its start tags in document order (the
  /// tags of an appended raw section, which is binary, are not parsed).
  class VtkXmlFile
  {
  public:
    /// Reads and tags the file; throws InputError for a missing file or one
    /// that is not VTK XML.
    explicit VtkXmlFile(const std::string &file_name);

    const std::string          &file_name() const { return name; }
    const std::vector<XmlTag>  &tags() const { return tag_list; }
    const XmlTag               &root() const { return tag_list.front(); }
    std::string                 content(const XmlTag &tag) const;

    /// The values of a DataArray tag (all components, point- or cell-major as
    /// stored), converted to double; 'expected' values (any number for
    /// any_size) or an error naming the array.
    std::vector<double> data_array(const XmlTag &tag, std::size_t expected) const;

  private:
    std::string         name, bytes;
    std::vector<XmlTag> tag_list;
    // Where the appended section's data start ('_' excluded), or npos.
    std::size_t appended_begin = std::string::npos;
    std::string appended_encoding;
    [[noreturn]] void fail(const std::string &what) const;
    /// The raw bytes of one array (header and blocks already undone).
    std::string payload(const XmlTag &tag, const std::string &format) const;
    std::string unpack(const std::string &stored, const std::string &array) const;
  };

  /// Decodes base64; padding may end one encoded block and a next follow (VTK
  /// encodes an array's header and its data apart).
  std::string decode_base64(const std::string &text);
} // namespace sluice
