// Copyright 2026 colcon-wasm contributors
// Licensed under the Apache License, Version 2.0

// The text of an uncaught C++ exception, for the crash report.
//
// Emscripten's exceptions are thrown as JS values (the thrown object's
// address): one that nothing catches reaches the runtime as a bare number.
// wasm_js' host calls this function with that address and the exception's
// type_info (from Emscripten's ExceptionInfo) to report what a native
// process prints when std::terminate ends it: the type and what().

#include <emscripten/emscripten.h>

#include <cxxabi.h>

#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <typeinfo>

// Emscripten's libc++abi: can a handler of `catch_type` catch an exception of
// `thrown_type`? Adjusts `*thrown` to the caught base's address.
extern "C" int __cxa_can_catch(
  const std::type_info * catch_type, const std::type_info * thrown_type, void ** thrown);

/// "<demangled type>\n<what()>" (what() only for std::exception), malloc'ed.
extern "C" EMSCRIPTEN_KEEPALIVE char * wasm_cpp_exception_text(
  void * thrown, const std::type_info * type)
{
  std::string text = "(unknown type)";
  if (type != nullptr) {
    int status = 0;
    char * name = abi::__cxa_demangle(type->name(), nullptr, nullptr, &status);
    text = (status == 0 && name != nullptr) ? name : type->name();
    std::free(name);
    void * adjusted = thrown;
    if (thrown != nullptr && __cxa_can_catch(&typeid(std::exception), type, &adjusted)) {
      text += "\n";
      text += static_cast<const std::exception *>(adjusted)->what();
    }
  }
  return strdup(text.c_str());
}
