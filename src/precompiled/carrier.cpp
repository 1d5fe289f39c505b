// The translation unit that carries a precompiled header (cmake/Precompiled.cmake); it holds no code.
