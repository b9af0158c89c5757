// Allocators whose containers leave new elements default-initialized (internal header).
//
// std::vector's resize(n) value-initializes its new elements: zeros for trivial types, which
// only cost stores when the values are written next anyway (the CUDB sweep's per-line lists,
// the region numbering's lists). An allocator deriving from DefaultInit constructs an element
// made without a value by default-initialization (left unset for trivial types) and every
// other one as std::allocator does.
#ifndef vbr_DefaultInitAllocator_h
#define vbr_DefaultInitAllocator_h

#include <memory>
#include <new>
#include <type_traits>
#include <utility>

namespace vbr
{

/// The construct members of such an allocator, on top of `Base` (an allocator whose own
/// construct they hide, or nothing).
struct NoAllocatorBase
{
};
template<typename Base = NoAllocatorBase>
struct DefaultInit : Base
{
  template<typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template<typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// std::allocator whose resize leaves new elements of trivial types unwritten, for arrays
/// grown to their size and then written through pointers: zeroing them first
/// (value-initialization) only cost stores (the CUDB sweep's per-line lists, 16,384 growths a
/// sweep on porous volumes; the corner set's points, written side by side by threads).
template<typename T>
struct Uninitialized : DefaultInit<std::allocator<T>>
{
  template<typename U>
  struct rebind
  {
    using other = Uninitialized<U>;
  };
  Uninitialized() = default;
  template<typename U>
  Uninitialized(const Uninitialized<U>&)
  {
  }
};

} // namespace vbr

#endif
