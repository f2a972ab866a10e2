#pragma once
// Compile-time lists of contact parts and their Cartesian product. The supported contact models are
// every combination of one part from each list (contact/laws.hpp); the run-time variant over them is
// generated here, so a new part enters every combination by being added to its list.
#include <variant>

namespace sedwave::forward::dem {

template <class... Ts>
struct TypeList {};

namespace type_list_detail {

template <class... Lists>
struct Concat {
  using type = TypeList<>;
};
template <class... A>
struct Concat<TypeList<A...>> {
  using type = TypeList<A...>;
};
template <class... A, class... B, class... Rest>
struct Concat<TypeList<A...>, TypeList<B...>, Rest...> {
  using type = typename Concat<TypeList<A..., B...>, Rest...>::type;
};

/// Puts Head in front of each tuple of a list of tuples.
template <class Head, class Tuples>
struct PrependEach;
template <class Head, class... Tuples>
struct PrependEach<Head, TypeList<Tuples...>> {
  template <class Tuple>
  struct One;
  template <class... Ts>
  struct One<TypeList<Ts...>> {
    using type = TypeList<Head, Ts...>;
  };
  using type = TypeList<typename One<Tuples>::type...>;
};

}  // namespace type_list_detail

/// Every way of choosing one type from each list, as a TypeList of TypeLists (first list outermost).
template <class... Lists>
struct CartesianProduct {
  using type = TypeList<TypeList<>>;
};
template <class... Heads, class... Rest>
struct CartesianProduct<TypeList<Heads...>, Rest...> {
  using type = typename type_list_detail::Concat<
      typename type_list_detail::PrependEach<Heads, typename CartesianProduct<Rest...>::type>::type...>::type;
};

/// std::variant<Template<choice...>...> over every choice of CartesianProduct<Lists...>.
template <template <class...> class Template, class... Lists>
struct VariantOfProduct {
  template <class Tuples>
  struct Apply;
  template <class... Tuples>
  struct Apply<TypeList<Tuples...>> {
    template <class Tuple>
    struct One;
    template <class... Ts>
    struct One<TypeList<Ts...>> {
      using type = Template<Ts...>;
    };
    using type = std::variant<typename One<Tuples>::type...>;
  };
  using type = typename Apply<typename CartesianProduct<Lists...>::type>::type;
};

/// Calls f(Part{}) -- a default-constructed tag -- for each part of a list, in order; f returns true
/// to stop. Used to find a part by its run-time name.
template <class... Parts, class F>
bool for_each_part(TypeList<Parts...>, F&& f) {
  return (f(static_cast<Parts*>(nullptr)) || ...);
}

}  // namespace sedwave::forward::dem
