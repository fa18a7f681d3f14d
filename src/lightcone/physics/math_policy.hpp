// The policy under which the black hole's kernels call Boost.Math (its elliptic integrals and
// functions, root finders and quadrature): double precision throughout, and no exceptions.
#pragma once

#include <boost/math/policies/policy.hpp>

namespace lightcone {

// Boost's default promotes double to long double (x87, several times slower), which no caller's
// tolerance needs. Its errors are ignored: an argument outside a function's domain gives NaN, and
// a root finder given no bracket returns one end of it (the callers bracket first), so that no
// library's message (which names Boost's functions) can reach the user.
using MathPolicy = boost::math::policies::policy<
    boost::math::policies::promote_double<false>,
    boost::math::policies::domain_error<boost::math::policies::ignore_error>,
    boost::math::policies::pole_error<boost::math::policies::ignore_error>,
    boost::math::policies::overflow_error<boost::math::policies::ignore_error>,
    boost::math::policies::evaluation_error<boost::math::policies::ignore_error>>;

}  // namespace lightcone
