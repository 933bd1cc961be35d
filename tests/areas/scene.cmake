# Scenes (issue 8): the scene model, its JSON format, the OBJ/PLY readers. Sources in tests/scene/.
cj_add_test(test_scene SOURCES scene/test_scene.c LIBS cj::scene)
cj_add_test(test_scene_json SOURCES scene/test_scene_json.c scene/scene_json_bad.c
  scene/scene_json_round_trip.c LIBS cj::scene)
target_compile_definitions(test_scene_json PRIVATE
  CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt"
  CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
cj_add_test(test_mesh_read SOURCES scene/test_mesh_read.c LIBS cj::surfaces)
# Image textures of a scene are read in viz/ (through the OpenImageIO adapter).
if(CJ_WITH_OIIO AND TARGET cj::viz)
  cj_add_test(test_scene_textures SOURCES scene/test_scene_textures.c LIBS cj::viz cj::scene)
  target_compile_definitions(test_scene_textures PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt"
    CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
endif()
