// glTF buffers and images read from disk (scene_io/gltf_files.h) under the OBJ loader's file
// rules: external buffers relative or absolute, FIFOs and folders refused without blocking, wrong
// sizes and missing files named in one short line, deep nesting refused.
#include "gltf_test_support.h"

namespace pm {
namespace {

// Buffers follow the OBJ loader's file rules: regular files only, relative to the glTF's folder
// unless absolute, and short messages naming the field.
class GltfBuffers : public Gltf {
 protected:
  GltfBuffers() {
    b_.node({{"mesh", b_.triangle_mesh()}});
    b_.add_camera_and_light();
  }
  // The message of loading the scene with this buffer; "" (and a failure) when it loads.
  std::string error_with(const json& buffer) {
    try {
      load_scene_file(write("scene.gltf", b_.gltf_text_with_buffer(buffer)));
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      EXPECT_LT(std::string(e.what()).size(), 400u) << e.what();
      return e.what();
    }
    ADD_FAILURE() << "loaded " << buffer.dump().substr(0, 200);
    return "";
  }
  json external(const std::string& uri, size_t length) { return {{"byteLength", length}, {"uri", uri}}; }
  GltfBuilder b_;
};

TEST_F(GltfBuffers, AnExternalBufferLoadsRelativeOrAbsolute) {
  write("mesh data.bin", b_.bytes());
  EXPECT_EQ(load_scene_file(write("scene.gltf", b_.gltf_text_with_buffer(external("mesh%20data.bin", b_.bytes().size()))))
                .triangle_count(), 1u);
  const std::string absolute = (dir_ / "mesh data.bin").string();
  EXPECT_EQ(load_scene_file(write("scene.gltf", b_.gltf_text_with_buffer(external(absolute, b_.bytes().size()))))
                .triangle_count(), 1u);
}

TEST_F(GltfBuffers, AFifoIsRefusedWithoutBlocking) {
  ASSERT_EQ(::mkfifo((dir_ / "pipe.bin").c_str(), 0644), 0);
  const std::string scene = write("scene.gltf", b_.gltf_text_with_buffer(external("pipe.bin", 12)));
  // In a child with an alarm: reading the FIFO used to block forever.
  EXPECT_EXIT(
      {
        ::alarm(20);
        try {
          load_scene_file(scene);
        } catch (const InputError& e) {
          std::exit(std::string(e.what()).find(": buffers[0].uri: 'pipe.bin' is not a regular file") != std::string::npos
                        ? 0 : 3);
        }
        std::exit(4);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST_F(GltfBuffers, AFolderIsRefused) {
  EXPECT_NE(error_with(external(".", 12)).find("buffers[0].uri: '.' is a folder, not a regular file"), std::string::npos);
}

TEST_F(GltfBuffers, AWrongByteLengthOfADataUriIsOneShortLine) {
  // 6 MB of base64 claimed to be 12 bytes: the message used to echo the whole URI.
  const std::string big(4500000, 'x');
  const std::string message =
      error_with({{"byteLength", 12}, {"uri", "data:application/octet-stream;base64," + base64(big)}});
  EXPECT_NE(message.find("buffers[0].byteLength: 12, but its data URI holds 4500000 bytes"), std::string::npos) << message;
  EXPECT_NE(error_with({{"byteLength", 12}, {"uri", "data:application/octet-stream;base64,@@@@"}})
                .find("buffers[0].uri: the data URI is not valid base64"), std::string::npos);
}

TEST_F(GltfBuffers, AFileOfTheWrongSizeIsNamedNotCalledMissing) {
  const std::string message = error_with(external("/etc/passwd", 12));
  EXPECT_NE(message.find("buffers[0].byteLength: 12, but '/etc/passwd' has "), std::string::npos) << message;
  EXPECT_EQ(message.find("not found"), std::string::npos) << message;
}

TEST_F(GltfBuffers, AMissingFileSaysWhereItWasLookedFor) {
  const std::string message = error_with(external("nope.bin", 12));
  EXPECT_NE(message.find("buffers[0].uri: 'nope.bin' not found (looked for '" + (dir_ / "nope.bin").string() + "')"),
            std::string::npos) << message;
}

TEST_F(GltfBuffers, ADeeplyNestedDocumentIsRefused) {
  std::string text = b_.gltf_text();
  text.insert(text.size() - 1, ", \"extras\": " + std::string(200, '[') + std::string(200, ']'));
  try {
    load_scene_file(write("deep.gltf", text));
    ADD_FAILURE() << "loaded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("JSON nested deeper than 100 levels"), std::string::npos) << e.what();
  }
}

TEST_F(GltfBuffers, AnImageThatIsAFifoDoesNotBlock) {
  ASSERT_EQ(::mkfifo((dir_ / "tex.png").c_str(), 0644), 0);
  b_.doc()["images"] = {{{"uri", "tex.png"}}};
  const std::string scene = write("scene.gltf", b_.gltf_text());
  EXPECT_EXIT(
      {
        ::alarm(20);
        SceneLoadReport report;
        std::exit(load_scene_file(scene, &report).triangle_count() == 1 ? 0 : 3);
      },
      ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace pm
