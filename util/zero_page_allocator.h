#pragma once
/// An allocator for large buffers that start as zeros, written later by many threads.
/// calloc hands out fresh pages the kernel has already zeroed, so nothing clears them a second
/// time, and each page's first touch (a page fault) falls to whoever writes it first — a
/// render's tiles, in parallel — instead of one thread up front. For a 512 x 512 film (21 MB)
/// the clearing and its faults were 5 % of a one-thread frame, all of it serial.
///
/// Value-initialising construction (std::vector's (n) constructor and resize()) writes nothing,
/// so a container may only grow into memory that is fresh from allocate(): build a new vector
/// rather than resize one that has shrunk or been cleared (Film::resize does).

#include <cstddef>
#include <cstdlib>
#include <new>
#include <utility>

namespace nenrin {

template <class T>
struct ZeroPageAllocator {
    using value_type = T;

    ZeroPageAllocator() = default;
    template <class U>
    ZeroPageAllocator(const ZeroPageAllocator<U>&) noexcept {}

    T* allocate(std::size_t n) {
        void* p = std::calloc(n, sizeof(T));
        if (p == nullptr) throw std::bad_alloc();
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t) noexcept { std::free(p); }

    /// Value-initialisation: the bytes are calloc's zeros already (T must be zero when all its
    /// bits are, as float and the integers are).
    template <class U>
    void construct(U*) noexcept {}
    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }

    friend bool operator==(const ZeroPageAllocator&, const ZeroPageAllocator&) { return true; }
};

}  // namespace nenrin
