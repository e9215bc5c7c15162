#include "link/photo_assembler.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace kapfix::link {
namespace {

kapfix::v1::Photo Chunk(const std::string& name, const std::string& file, std::size_t offset,
                        std::size_t size) {
  kapfix::v1::Photo chunk;
  chunk.mutable_metadata()->set_file_name(name);
  chunk.set_offset_bytes(offset);
  chunk.set_total_bytes(file.size());
  chunk.set_data(file.substr(offset, size));
  return chunk;
}

TEST(LinkPhotoAssemblerTest, AssemblesChunksArrivingOutOfOrder) {
  const std::string file = "0123456789abcdef";
  PhotoAssembler assembler;
  EXPECT_FALSE(assembler.Add(Chunk("p.png", file, 8, 8)).has_value());
  const auto photo = assembler.Add(Chunk("p.png", file, 0, 8));
  ASSERT_TRUE(photo.has_value());
  EXPECT_EQ(photo->bytes, file);
  EXPECT_EQ(assembler.incomplete(), 0U);
}

TEST(LinkPhotoAssemblerTest, RepeatedChunkDoesNotCompleteAPhoto) {
  const std::string file = "0123456789abcdef";
  PhotoAssembler assembler;
  EXPECT_FALSE(assembler.Add(Chunk("p.png", file, 0, 8)).has_value());
  EXPECT_FALSE(assembler.Add(Chunk("p.png", file, 0, 8)).has_value());
  EXPECT_EQ(assembler.incomplete(), 1U);
}

TEST(LinkPhotoAssemblerTest, RefusesANameWithAPath) {
  PhotoAssembler assembler;
  EXPECT_FALSE(assembler.Add(Chunk("../evil", "x", 0, 1)).has_value());
  EXPECT_EQ(assembler.incomplete(), 0U);
}

TEST(LinkPhotoAssemblerTest, SaveWritesTheWholeFileAndNoTemporary) {
  std::string pattern = (std::filesystem::temp_directory_path() / "kapfix_photo_XXXXXX").string();
  ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
  const std::filesystem::path folder = pattern;
  AssembledPhoto photo;
  photo.metadata.set_file_name("p.png");
  photo.bytes = std::string("\x89PNG\0data", 9);
  const auto path = PhotoAssembler::Save(photo, folder);
  std::ifstream in(path, std::ios::binary);
  std::stringstream content;
  content << in.rdbuf();
  EXPECT_EQ(content.str(), photo.bytes);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder),
                          std::filesystem::directory_iterator()),
            1);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace kapfix::link
