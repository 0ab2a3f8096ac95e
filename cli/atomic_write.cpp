#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <unistd.h>

#include "commands.hpp"

namespace superball::cli {

void write_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("write_file_atomically(): " + path + ": cannot write here");
    out << text;
    out.flush();
    if (!out) {
      std::remove(tmp.c_str());
      throw std::runtime_error("write_file_atomically(): " + path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("write_file_atomically(): " + path + ": cannot rename the temporary file into place");
  }
}

void write_output(const std::string& path, const std::string& text) {
  if (path.empty())
    std::cout << text;
  else
    write_file_atomically(path, text);
}

}  // namespace superball::cli
