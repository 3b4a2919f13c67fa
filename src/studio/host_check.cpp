#include "studio/host_check.h"

#include <algorithm>

#include <arpa/inet.h>
#include <fmt/format.h>

#include "motiongraph/core/text.h"

namespace mg::studio {

namespace {

bool is_address(const std::string& host, int family) {
  unsigned char bytes[16];
  return inet_pton(family, host.c_str(), bytes) == 1;
}

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '.' ||
         c == '_';
}

}  // namespace

std::string host_of_header(std::string_view header) {
  std::string_view host = header;
  std::string_view port;
  if (host.starts_with('[')) {
    const size_t close = host.find(']');
    if (close == std::string_view::npos) return "";
    const std::string inside(host.substr(1, close - 1));
    if (!is_address(inside, AF_INET6)) return "";
    port = host.substr(close + 1);
    if (!port.empty() && !port.starts_with(':')) return "";
    host = host.substr(0, close + 1);
  } else {
    const size_t colon = host.find(':');
    if (colon != std::string_view::npos) {
      port = host.substr(colon);
      host = host.substr(0, colon);
    }
    if (host.ends_with('.')) host.remove_suffix(1);
    if (host.empty() || !std::all_of(host.begin(), host.end(), name_char)) return "";
  }
  if (!port.empty()) {
    port.remove_prefix(1);
    if (port.size() > 5 || !is_ascii_digits(port)) {
      return "";
    }
  }
  return ascii_lower(host);
}

bool host_allowed(std::string_view header, const std::vector<std::string>& allowed) {
  const std::string host = host_of_header(header);
  if (host.empty()) return false;
  if (host.starts_with('[') || is_address(host, AF_INET)) return true;
  if (host == "localhost" || host.ends_with(".localhost")) return true;
  return std::any_of(allowed.begin(), allowed.end(), [&](const std::string& entry) {
    if (entry.starts_with('.')) return host == entry.substr(1) || host.ends_with(entry);
    return host == entry;
  });
}

Status check_allowed_host(std::string_view entry) {
  if (entry.empty()) return Error{"", 0, "an empty host name"};
  if (entry.find("://") != std::string_view::npos || entry.find('/') != std::string_view::npos) {
    return Error{"", 0, fmt::format("{}: give the host name alone, not a URL", quoted(entry))};
  }
  const std::string text(entry);
  if (entry.starts_with('[') || is_address(text, AF_INET6) || is_address(text, AF_INET)) {
    return Error{"", 0, fmt::format("{}: an IP address needs no --allow-host (addresses are always answered)",
                                    quoted(entry))};
  }
  if (entry.find(':') != std::string_view::npos) {
    return Error{"", 0, fmt::format("{}: give the host name alone, without a port", quoted(entry))};
  }
  // Labels of letters, digits, '-' and '_', not starting or ending with '-', between single dots;
  // one dot before the first: every name under the rest.
  const std::string_view name = entry.starts_with('.') ? entry.substr(1) : entry;
  bool labels_ok = !name.empty();
  for (size_t from = 0; labels_ok && from <= name.size();) {
    const size_t dot = std::min(name.find('.', from), name.size());
    const std::string_view label = name.substr(from, dot - from);
    labels_ok = !label.empty() && label.front() != '-' && label.back() != '-' &&
                std::all_of(label.begin(), label.end(), [](char c) { return name_char(c) && c != '.'; });
    from = dot + 1;
  }
  if (!labels_ok) {
    return Error{"", 0,
                 fmt::format("{}: not a host name (labels of letters, digits, '-' and '_' between single dots)",
                             quoted(entry))};
  }
  return Ok{};
}

}  // namespace mg::studio
