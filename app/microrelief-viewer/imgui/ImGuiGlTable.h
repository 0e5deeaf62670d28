// Forced-included (-include) into Debian's imgui_impl_opengl3.cpp, which is compiled with
// IMGUI_IMPL_OPENGL_LOADER_CUSTOM: instead of the backend's own gl3w-style loader (which
// dlopens libGL and keeps a process-wide pointer table), every gl* name it calls becomes
// a call through the window context's glad table (include/microrelief/gl/Gl.h), like all GL in the
// project. The list is what imgui_impl_opengl3.cpp 1.86 calls; a name missing here fails
// to compile (glad --mx declares no gl* functions), it can never reach libGL silently.
#pragma once

#include <glad/gl.h>

// Set by setImGuiGlTable() (ImGuiGlTable.cpp) before ImGui_ImplOpenGL3_Init.
extern const GladGLContext* microrelief_imgui_gl;

#define glActiveTexture (microrelief_imgui_gl->ActiveTexture)
#define glAttachShader (microrelief_imgui_gl->AttachShader)
#define glBindBuffer (microrelief_imgui_gl->BindBuffer)
#define glBindSampler (microrelief_imgui_gl->BindSampler)
#define glBindTexture (microrelief_imgui_gl->BindTexture)
#define glBindVertexArray (microrelief_imgui_gl->BindVertexArray)
#define glBlendEquation (microrelief_imgui_gl->BlendEquation)
#define glBlendEquationSeparate (microrelief_imgui_gl->BlendEquationSeparate)
#define glBlendFuncSeparate (microrelief_imgui_gl->BlendFuncSeparate)
#define glBufferData (microrelief_imgui_gl->BufferData)
#define glBufferSubData (microrelief_imgui_gl->BufferSubData)
#define glCompileShader (microrelief_imgui_gl->CompileShader)
#define glCreateProgram (microrelief_imgui_gl->CreateProgram)
#define glCreateShader (microrelief_imgui_gl->CreateShader)
#define glDeleteBuffers (microrelief_imgui_gl->DeleteBuffers)
#define glDeleteProgram (microrelief_imgui_gl->DeleteProgram)
#define glDeleteShader (microrelief_imgui_gl->DeleteShader)
#define glDeleteTextures (microrelief_imgui_gl->DeleteTextures)
#define glDeleteVertexArrays (microrelief_imgui_gl->DeleteVertexArrays)
#define glDetachShader (microrelief_imgui_gl->DetachShader)
#define glDisable (microrelief_imgui_gl->Disable)
#define glDrawElements (microrelief_imgui_gl->DrawElements)
#define glDrawElementsBaseVertex (microrelief_imgui_gl->DrawElementsBaseVertex)
#define glEnable (microrelief_imgui_gl->Enable)
#define glEnableVertexAttribArray (microrelief_imgui_gl->EnableVertexAttribArray)
#define glGenBuffers (microrelief_imgui_gl->GenBuffers)
#define glGenTextures (microrelief_imgui_gl->GenTextures)
#define glGenVertexArrays (microrelief_imgui_gl->GenVertexArrays)
#define glGetAttribLocation (microrelief_imgui_gl->GetAttribLocation)
#define glGetIntegerv (microrelief_imgui_gl->GetIntegerv)
#define glGetProgramInfoLog (microrelief_imgui_gl->GetProgramInfoLog)
#define glGetProgramiv (microrelief_imgui_gl->GetProgramiv)
#define glGetShaderInfoLog (microrelief_imgui_gl->GetShaderInfoLog)
#define glGetShaderiv (microrelief_imgui_gl->GetShaderiv)
#define glGetString (microrelief_imgui_gl->GetString)
#define glGetStringi (microrelief_imgui_gl->GetStringi)
#define glGetUniformLocation (microrelief_imgui_gl->GetUniformLocation)
#define glIsEnabled (microrelief_imgui_gl->IsEnabled)
#define glLinkProgram (microrelief_imgui_gl->LinkProgram)
#define glPixelStorei (microrelief_imgui_gl->PixelStorei)
#define glPolygonMode (microrelief_imgui_gl->PolygonMode)
#define glScissor (microrelief_imgui_gl->Scissor)
#define glShaderSource (microrelief_imgui_gl->ShaderSource)
#define glTexImage2D (microrelief_imgui_gl->TexImage2D)
#define glTexParameteri (microrelief_imgui_gl->TexParameteri)
#define glUniform1i (microrelief_imgui_gl->Uniform1i)
#define glUniformMatrix4fv (microrelief_imgui_gl->UniformMatrix4fv)
#define glUseProgram (microrelief_imgui_gl->UseProgram)
#define glVertexAttribPointer (microrelief_imgui_gl->VertexAttribPointer)
#define glViewport (microrelief_imgui_gl->Viewport)
