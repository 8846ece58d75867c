// A C++ result object whose lifetime is bound to a PostgreSQL memory context, so that emitting
// it (palloc, tuplestore_putvalues: both may longjmp) never leaks it: if an error unwinds past
// the entry point, the context's reset callback deletes the object. Include after core headers.
#pragma once

#include <cstring>
#include <utility>

#include "pg/postgres_headers.hpp"

namespace streetgen::pg {

template <class T>
class OwnedResult {  // trivially destructible on purpose: it may be skipped by a longjmp
 public:
  // Phase 1: registers the deleter with CurrentMemoryContext.
  static OwnedResult create() {
    auto* callback = static_cast<MemoryContextCallback*>(palloc0(sizeof(MemoryContextCallback)));
    callback->func = &OwnedResult::destroy;
    callback->arg = nullptr;
    MemoryContextRegisterResetCallback(CurrentMemoryContext, callback);
    return OwnedResult(callback);
  }

  // Phase 2 (inside guarded_call): may throw; touches no PostgreSQL function.
  template <class... Args>
  T& emplace(Args&&... args) {
    release();
    T* object = new T(std::forward<Args>(args)...);
    callback_->arg = object;
    return *object;
  }

  T& operator*() const noexcept { return *static_cast<T*>(callback_->arg); }
  T* operator->() const noexcept { return static_cast<T*>(callback_->arg); }

  // Phase 3, after emitting: frees now rather than at the context's reset.
  void release() noexcept {
    destroy(callback_->arg);
    callback_->arg = nullptr;
  }

 private:
  explicit OwnedResult(MemoryContextCallback* callback) : callback_(callback) {}
  static void destroy(void* object) noexcept { delete static_cast<T*>(object); }
  MemoryContextCallback* callback_;
};

// Copies bytes into a new palloc'd bytea (phase 3).
template <class Bytes>
bytea* to_bytea(const Bytes& bytes) {
  auto* out = static_cast<bytea*>(palloc(VARHDRSZ + bytes.size()));
  SET_VARSIZE(out, VARHDRSZ + bytes.size());
  std::memcpy(VARDATA(out), bytes.data(), bytes.size());
  return out;
}

}  // namespace streetgen::pg
