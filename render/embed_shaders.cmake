# Writes a C++ source holding every GLSL file of shaders/ as a string, so an installed
# brdfrig renders without the source tree. Run as: cmake -DSHADER_DIR=.. -DOUTPUT=.. -P this
file(GLOB shader_files RELATIVE ${SHADER_DIR} ${SHADER_DIR}/*.glsl ${SHADER_DIR}/*.vert
     ${SHADER_DIR}/*.frag)
list(SORT shader_files)
set(content "// Generated from shaders/ by render/embed_shaders.cmake. Do not edit.\n")
string(APPEND content "#include \"render/shader_sources.h\"\n\nnamespace brdfrig::render {\n")
string(APPEND content "const std::map<std::string, std::string>& EmbeddedShaders() {\n")
string(APPEND content "  static const std::map<std::string, std::string> shaders = {\n")
foreach(name IN LISTS shader_files)
  file(READ ${SHADER_DIR}/${name} text)
  string(APPEND content "      {\"${name}\", R\"glsl(${text})glsl\"},\n")
endforeach()
string(APPEND content "  };\n  return shaders;\n}\n}  // namespace brdfrig::render\n")
file(WRITE ${OUTPUT}.tmp "${content}")
file(COPY_FILE ${OUTPUT}.tmp ${OUTPUT} ONLY_IF_DIFFERENT)
