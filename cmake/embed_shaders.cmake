# Writes OUTPUT, a C++ file defining one string per shader file in SHADER_DIR:
# lightcone::shader_sources::<name>_<extension> (common.glsl -> common_glsl).
file(GLOB shaders "${SHADER_DIR}/*.glsl" "${SHADER_DIR}/*.vert" "${SHADER_DIR}/*.frag"
  "${SHADER_DIR}/*.tesc" "${SHADER_DIR}/*.tese")
list(SORT shaders)
set(text "// Generated from src/lightcone/raster/shaders by cmake/embed_shaders.cmake.\n")
string(APPEND text "#include \"lightcone/raster/shader_sources.hpp\"\n\n")
string(APPEND text "namespace lightcone::shader_sources {\n")
foreach(shader ${shaders})
  get_filename_component(name "${shader}" NAME)
  string(REPLACE "." "_" symbol "${name}")
  file(READ "${shader}" source)
  string(APPEND text "const char* const ${symbol} = R\"glsl(${source})glsl\";\n")
endforeach()
string(APPEND text "}  // namespace lightcone::shader_sources\n")
file(WRITE "${OUTPUT}.new" "${text}")
file(COPY_FILE "${OUTPUT}.new" "${OUTPUT}" ONLY_IF_DIFFERENT)
file(REMOVE "${OUTPUT}.new")
