/* Generator headers, one per generator; included by banyan.h. */
#ifndef BANYAN_GENERATORS_H
#define BANYAN_GENERATORS_H
#endif
