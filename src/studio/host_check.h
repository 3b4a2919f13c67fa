// The names the studio answers to. A page of another site can reach a server on this machine
// by DNS rebinding: its own name, resolved first to its server and then to 127.0.0.1, makes
// the browser send it the studio's answers as the page's own origin (the Origin check sees the
// same name on both sides). Its requests carry that name in the Host header, so the studio
// answers only requests addressed to an IP address, to localhost, or to a name the user allows.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "motiongraph/core/error.h"

namespace mg::studio {

// The host of a Host header ("name", "name:port", "[v6 address]:port"), lower case, without
// the port or a trailing dot; empty when the header is not of that form.
std::string host_of_header(std::string_view header);

// Whether a request whose Host header is `header` is answered: an IPv4 or IPv6 address,
// localhost or a name under .localhost (RFC 6761: always this machine), or a name in `allowed`
// (lower case; an entry ".example.org" allows example.org and every name under it).
bool host_allowed(std::string_view header, const std::vector<std::string>& allowed);

// An entry of --allow-host: a host name ("studio.lan", ".lan"), not a URL or a name with a
// port; the error says which part is wrong.
Status check_allowed_host(std::string_view entry);

}  // namespace mg::studio
