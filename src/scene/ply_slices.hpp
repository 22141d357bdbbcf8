#pragma once
// A binary PLY file read by slices of its records, never whole: the header once, then any range
// of vertices or faces from its offset (a rank's slice under --distribute data,
// src/regions/sliced_share.hpp). For files where record i of an element lies at a known offset:
// binary, the elements before the faces of fixed size (no lists), and the faces all triangles in
// records of one size (each record read is checked to hold 3 indices: a file whose polygons sum
// to the same size is found out by whoever reads a record that does not). The values are those
// PlyMeshStream reads (the same layout, float conversion, colour normalisation and index checks),
// so the triangles are the loader's.
#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "src/scene/ply_binary.hpp"

namespace lzb {

class PlySlices {
 public:
  // Reads the header. Returns nullptr with `why` set for a file not read by slices (not binary, an
  // element of variable size before the faces, faces of another size than a triangle's, a file
  // too short for its faces, or one the loader reads otherwise): the caller then streams or loads
  // it, which reports what is wrong with it. Throws InputError naming the file as the loader
  // would refuse its header.
  static std::unique_ptr<PlySlices> open(const std::filesystem::path& path, std::string& why);

  const std::string& where() const { return where_; }
  uint64_t vertices() const { return vertices_; }
  uint64_t faces() const { return faces_; }
  bool coloured() const;
  // Vertices [begin, end): positions in the file's frame, as floats, and their colours
  // normalised (left empty for a file without colours).
  void readVertices(uint64_t begin, uint64_t end, std::vector<glm::vec3>& positions,
                    std::vector<glm::vec3>& colours);
  // What readFaces read: faces [begin, stop), and why it stopped before the end.
  struct FaceRead {
    uint64_t stop = 0;
    bool notTriangle = false;  // face `stop` does not hold three indices (other polygons)
    std::string error;         // else, when set: why face `stop` is malformed (as the loader says)
  };
  // Faces [begin, end) appended to `indices`, three vertex indices each, up to the first record
  // that does not hold three or holds an index past the vertices. Which of two ranks' stops
  // counts is the caller's to decide (a record after one that is not a triangle is misread).
  FaceRead readFaces(uint64_t begin, uint64_t end, std::vector<uint32_t>& indices);
  // Bytes read from the file so far, the header's included.
  uint64_t bytesRead() const { return bytesRead_; }

 private:
  explicit PlySlices(const std::filesystem::path& path);
  PlyReader reader(uint64_t offset, uint64_t end) const;

  std::filesystem::path path_;
  std::string where_;
  PlyHeader header_;
  PlyMeshLayout layout_;
  uint64_t vertices_ = 0, faces_ = 0;
  uint64_t vertexData_ = 0, vertexStride_ = 0;  // the vertex element's offset and record size
  uint64_t faceData_ = 0, faceStride_ = 0;      // the same of the faces (triangles)
  uint64_t indexAt_ = 0;                        // the index list's offset in a face record
  uint64_t bytesRead_ = 0;
};

}  // namespace lzb
