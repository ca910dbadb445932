// The number of fields of an aggregate (a struct without constructors or bases), at compile
// time: the most initialisers `T{...}` accepts, each one a value that converts to anything
// (the technique of Boost.PFR). The options table (src/solver/solver_options.cpp) uses it to
// notice a field of SolverOptions that has no option.
#pragma once

#include <cstddef>
#include <utility>

namespace hemirad {

namespace aggregate_detail {

/// Converts to any field type (declared only: used in unevaluated contexts).
struct AnyField {
    template <class T> operator T() const;
};

template <class T, std::size_t... I> constexpr bool takes(std::index_sequence<I...>) {
    return requires {
        T{(void(I), AnyField{})...};
    };
}

template <class T, std::size_t N> constexpr std::size_t count_from() {
    if constexpr (takes<T>(std::make_index_sequence<N + 1>{}))
        return count_from<T, N + 1>();
    else
        return N;
}

} // namespace aggregate_detail

/// Fields of the aggregate T (a nested struct counts as one field).
template <class T> constexpr std::size_t field_count() {
    return aggregate_detail::count_from<T, 0>();
}

} // namespace hemirad
