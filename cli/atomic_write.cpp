#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <unistd.h>

#include "commands.hpp"

namespace superball::cli {

struct Output::Impl {
  std::string path, tmp;
  std::ofstream file;
  bool committed = false;
};

Output::Output(std::string path) : impl_(std::make_unique<Impl>()) {
  impl_->path = std::move(path);
  if (impl_->path.empty() || impl_->path == "-") return;
  impl_->tmp = impl_->path + ".tmp." + std::to_string(::getpid());
  impl_->file.open(impl_->tmp, std::ios::binary | std::ios::trunc);
  if (!impl_->file) throw OutputError(impl_->path + ": cannot write here");
}

Output::~Output() {
  if (!impl_->tmp.empty() && !impl_->committed) {
    impl_->file.close();
    std::remove(impl_->tmp.c_str());
  }
}

void Output::write(std::string_view text) {
  std::ostream& out = impl_->tmp.empty() ? std::cout : impl_->file;
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw OutputError((impl_->tmp.empty() ? std::string("standard output") : impl_->path) + ": write failed");
}

void Output::commit() {
  if (impl_->tmp.empty()) {
    std::cout.flush();
    if (!std::cout) throw OutputError("standard output: write failed");
    return;
  }
  impl_->file.flush();
  impl_->file.close();
  if (!impl_->file) throw OutputError(impl_->path + ": write failed");
  if (std::rename(impl_->tmp.c_str(), impl_->path.c_str()) != 0)
    throw OutputError(impl_->path + ": cannot rename the temporary file into place");
  impl_->committed = true;
}

void write_output(const std::string& path, const std::string& text) {
  Output out(path);
  out.write(text);
  out.commit();
}

void write_file_atomically(const std::string& path, const std::string& text) { write_output(path, text); }

}  // namespace superball::cli
