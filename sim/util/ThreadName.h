#pragma once
// Names the calling thread so that debuggers, `top -H` and the tests can tell Wisp's threads from
// the ones the OpenGL driver and Qt start. Linux keeps at most 15 characters of a name.
#include <pthread.h>

namespace wisp {

inline void nameThisThread(const char* name)
{
    pthread_setname_np(pthread_self(), name);
}

} // namespace wisp
