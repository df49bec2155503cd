// The last accepted values of a class's YADE attributes, for a postLoad that refuses an assignment:
// it puts every attribute back, so that one bad value does not make every later assignment fail.
// The snapshot is generated from the attribute list that the class gives YADE_CLASS_BASE_DOC_ATTRS_*,
// so a new attribute is part of it without being named a second time.
#pragma once

#include <boost/preprocessor/seq/for_each.hpp>
#include <boost/preprocessor/tuple/elem.hpp>

// One element of YADE's attribute list: (type, name, default, flags, docstring).
#define PENDULAR_SNAPSHOT_MEMBER(r, data, attr) BOOST_PP_TUPLE_ELEM(5, 0, attr) BOOST_PP_TUPLE_ELEM(5, 1, attr);
#define PENDULAR_SNAPSHOT_TAKE(r, snapshot, attr) snapshot.BOOST_PP_TUPLE_ELEM(5, 1, attr) = BOOST_PP_TUPLE_ELEM(5, 1, attr);
#define PENDULAR_SNAPSHOT_PUT(r, snapshot, attr) BOOST_PP_TUPLE_ELEM(5, 1, attr) = snapshot.BOOST_PP_TUPLE_ELEM(5, 1, attr);

// In a class body: `Checked`, one member per attribute of `attrs` (same type and name); checked()
// copies the attributes into a Checked, restore() copies them back.
#define PENDULAR_ATTR_SNAPSHOT(attrs)                                                                                                                          \
	struct Checked {                                                                                                                                       \
		BOOST_PP_SEQ_FOR_EACH(PENDULAR_SNAPSHOT_MEMBER, ~, attrs)                                                                                      \
	};                                                                                                                                                     \
	Checked checked() const                                                                                                                                \
	{                                                                                                                                                      \
		Checked snapshot;                                                                                                                              \
		BOOST_PP_SEQ_FOR_EACH(PENDULAR_SNAPSHOT_TAKE, snapshot, attrs)                                                                                 \
		return snapshot;                                                                                                                               \
	}                                                                                                                                                      \
	void restore(const Checked& snapshot) { BOOST_PP_SEQ_FOR_EACH(PENDULAR_SNAPSHOT_PUT, snapshot, attrs) }
