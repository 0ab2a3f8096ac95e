#pragma once
/// \file text_sink.hpp
/// Where the reports of many points (a map's grid, a sweep's rows) go as
/// they are made.

#include <functional>
#include <string_view>

namespace superball::present {

/// A piece of an output's text: a front writes the pieces as they come, in
/// order (the write_… functions hand them over so, one call at a time; with
/// several threads, from a thread of their own, so that the writing of a
/// block overlaps the formatting of the next ones).  An exception a sink
/// throws comes out of the write_… function.
using TextSink = std::function<void(std::string_view text)>;

}  // namespace superball::present
