// OSMesa and the OpenGL functions the llvmpipe reference calls, through pointers that loadGlApi()
// takes from libOSMesa at run time (dlopen), so that the tessera executable does not link Mesa: a
// linked libOSMesa brings LLVM with it, and every command (`tessera --version` as much as a
// render) paid for loading and relocating it at start-up. Include it after <GL/gl.h>,
// <GL/glext.h> (with GL_GLEXT_PROTOTYPES) and <GL/osmesa.h>: from here on each name below calls
// through its pointer. Private to the llvmpipe reference (bench/llvmpipe_*.cpp).
#pragma once

#include <string>

#if !defined(GL_GLEXT_PROTOTYPES)
#define GL_GLEXT_PROTOTYPES 1  // the prototypes that decltype reads below
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

namespace tessera::bench {

// The functions, each once.
#define TESSERA_GL_API(X)             \
  X(OSMesaCreateContextExt)           \
  X(OSMesaDestroyContext)             \
  X(OSMesaGetCurrentContext)          \
  X(OSMesaGetIntegerv)                \
  X(OSMesaGetProcAddress)             \
  X(OSMesaMakeCurrent)                \
  X(glActiveTexture)                  \
  X(glAttachShader)                   \
  X(glBindAttribLocation)             \
  X(glBindBuffer)                     \
  X(glBindFramebuffer)                \
  X(glBindRenderbuffer)               \
  X(glBindTexture)                    \
  X(glBlitFramebuffer)                \
  X(glBufferData)                     \
  X(glBufferSubData)                  \
  X(glCheckFramebufferStatus)         \
  X(glClear)                          \
  X(glClearColor)                     \
  X(glClearDepth)                     \
  X(glCompileShader)                  \
  X(glCreateProgram)                  \
  X(glCreateShader)                   \
  X(glCullFace)                       \
  X(glDeleteBuffers)                  \
  X(glDeleteFramebuffers)             \
  X(glDeleteProgram)                  \
  X(glDeleteRenderbuffers)            \
  X(glDeleteShader)                   \
  X(glDeleteTextures)                 \
  X(glDepthFunc)                      \
  X(glDisable)                        \
  X(glDisableVertexAttribArray)       \
  X(glDrawArrays)                     \
  X(glDrawElements)                   \
  X(glEnable)                         \
  X(glEnableVertexAttribArray)        \
  X(glFinish)                         \
  X(glFramebufferRenderbuffer)        \
  X(glFrontFace)                      \
  X(glGenBuffers)                     \
  X(glGenFramebuffers)                \
  X(glGenRenderbuffers)               \
  X(glGenTextures)                    \
  X(glGetError)                       \
  X(glGetProgramInfoLog)              \
  X(glGetProgramiv)                   \
  X(glGetRenderbufferParameteriv)     \
  X(glGetShaderInfoLog)               \
  X(glGetShaderiv)                    \
  X(glGetString)                      \
  X(glGetUniformLocation)             \
  X(glLinkProgram)                    \
  X(glPixelStorei)                    \
  X(glReadPixels)                     \
  X(glRenderbufferStorageMultisample) \
  X(glShaderSource)                   \
  X(glTexImage2D)                     \
  X(glTexParameteri)                  \
  X(glUniform1f)                      \
  X(glUniform1i)                      \
  X(glUniform2f)                      \
  X(glUniform3f)                      \
  X(glUniform3fv)                     \
  X(glUniform4f)                      \
  X(glUniform4fv)                     \
  X(glUniformMatrix3fv)               \
  X(glUniformMatrix4fv)               \
  X(glUseProgram)                     \
  X(glVertexAttribPointer)            \
  X(glViewport)

struct GlApi {
#define TESSERA_GL_POINTER(name) decltype(&::name) name = nullptr;
  TESSERA_GL_API(TESSERA_GL_POINTER)
#undef TESSERA_GL_POINTER
};

// The loaded pointers (all null before loadGlApi() succeeds).
const GlApi& glApi();

// Opens libOSMesa and fills glApi(), once per process (later calls return the first result):
// "" on success, else what is missing, in a user's words.
std::string loadGlApi();

}  // namespace tessera::bench

// Every call below goes through the pointers (gl_api.cpp, which fills them, names the members).
#if !defined(TESSERA_GL_API_NO_MACROS)
#define OSMesaCreateContextExt ::tessera::bench::glApi().OSMesaCreateContextExt
#define OSMesaDestroyContext ::tessera::bench::glApi().OSMesaDestroyContext
#define OSMesaGetCurrentContext ::tessera::bench::glApi().OSMesaGetCurrentContext
#define OSMesaGetIntegerv ::tessera::bench::glApi().OSMesaGetIntegerv
#define OSMesaGetProcAddress ::tessera::bench::glApi().OSMesaGetProcAddress
#define OSMesaMakeCurrent ::tessera::bench::glApi().OSMesaMakeCurrent
#define glActiveTexture ::tessera::bench::glApi().glActiveTexture
#define glAttachShader ::tessera::bench::glApi().glAttachShader
#define glBindAttribLocation ::tessera::bench::glApi().glBindAttribLocation
#define glBindBuffer ::tessera::bench::glApi().glBindBuffer
#define glBindFramebuffer ::tessera::bench::glApi().glBindFramebuffer
#define glBindRenderbuffer ::tessera::bench::glApi().glBindRenderbuffer
#define glBindTexture ::tessera::bench::glApi().glBindTexture
#define glBlitFramebuffer ::tessera::bench::glApi().glBlitFramebuffer
#define glBufferData ::tessera::bench::glApi().glBufferData
#define glBufferSubData ::tessera::bench::glApi().glBufferSubData
#define glCheckFramebufferStatus ::tessera::bench::glApi().glCheckFramebufferStatus
#define glClear ::tessera::bench::glApi().glClear
#define glClearColor ::tessera::bench::glApi().glClearColor
#define glClearDepth ::tessera::bench::glApi().glClearDepth
#define glCompileShader ::tessera::bench::glApi().glCompileShader
#define glCreateProgram ::tessera::bench::glApi().glCreateProgram
#define glCreateShader ::tessera::bench::glApi().glCreateShader
#define glCullFace ::tessera::bench::glApi().glCullFace
#define glDeleteBuffers ::tessera::bench::glApi().glDeleteBuffers
#define glDeleteFramebuffers ::tessera::bench::glApi().glDeleteFramebuffers
#define glDeleteProgram ::tessera::bench::glApi().glDeleteProgram
#define glDeleteRenderbuffers ::tessera::bench::glApi().glDeleteRenderbuffers
#define glDeleteShader ::tessera::bench::glApi().glDeleteShader
#define glDeleteTextures ::tessera::bench::glApi().glDeleteTextures
#define glDepthFunc ::tessera::bench::glApi().glDepthFunc
#define glDisable ::tessera::bench::glApi().glDisable
#define glDisableVertexAttribArray ::tessera::bench::glApi().glDisableVertexAttribArray
#define glDrawArrays ::tessera::bench::glApi().glDrawArrays
#define glDrawElements ::tessera::bench::glApi().glDrawElements
#define glEnable ::tessera::bench::glApi().glEnable
#define glEnableVertexAttribArray ::tessera::bench::glApi().glEnableVertexAttribArray
#define glFinish ::tessera::bench::glApi().glFinish
#define glFramebufferRenderbuffer ::tessera::bench::glApi().glFramebufferRenderbuffer
#define glFrontFace ::tessera::bench::glApi().glFrontFace
#define glGenBuffers ::tessera::bench::glApi().glGenBuffers
#define glGenFramebuffers ::tessera::bench::glApi().glGenFramebuffers
#define glGenRenderbuffers ::tessera::bench::glApi().glGenRenderbuffers
#define glGenTextures ::tessera::bench::glApi().glGenTextures
#define glGetError ::tessera::bench::glApi().glGetError
#define glGetProgramInfoLog ::tessera::bench::glApi().glGetProgramInfoLog
#define glGetProgramiv ::tessera::bench::glApi().glGetProgramiv
#define glGetRenderbufferParameteriv ::tessera::bench::glApi().glGetRenderbufferParameteriv
#define glGetShaderInfoLog ::tessera::bench::glApi().glGetShaderInfoLog
#define glGetShaderiv ::tessera::bench::glApi().glGetShaderiv
#define glGetString ::tessera::bench::glApi().glGetString
#define glGetUniformLocation ::tessera::bench::glApi().glGetUniformLocation
#define glLinkProgram ::tessera::bench::glApi().glLinkProgram
#define glPixelStorei ::tessera::bench::glApi().glPixelStorei
#define glReadPixels ::tessera::bench::glApi().glReadPixels
#define glRenderbufferStorageMultisample ::tessera::bench::glApi().glRenderbufferStorageMultisample
#define glShaderSource ::tessera::bench::glApi().glShaderSource
#define glTexImage2D ::tessera::bench::glApi().glTexImage2D
#define glTexParameteri ::tessera::bench::glApi().glTexParameteri
#define glUniform1f ::tessera::bench::glApi().glUniform1f
#define glUniform1i ::tessera::bench::glApi().glUniform1i
#define glUniform2f ::tessera::bench::glApi().glUniform2f
#define glUniform3f ::tessera::bench::glApi().glUniform3f
#define glUniform3fv ::tessera::bench::glApi().glUniform3fv
#define glUniform4f ::tessera::bench::glApi().glUniform4f
#define glUniform4fv ::tessera::bench::glApi().glUniform4fv
#define glUniformMatrix3fv ::tessera::bench::glApi().glUniformMatrix3fv
#define glUniformMatrix4fv ::tessera::bench::glApi().glUniformMatrix4fv
#define glUseProgram ::tessera::bench::glApi().glUseProgram
#define glVertexAttribPointer ::tessera::bench::glApi().glVertexAttribPointer
#define glViewport ::tessera::bench::glApi().glViewport
#endif
