// The values of young_laplace_table (data/young_laplace_table.bin, float32, written by
// tools/generate_young_laplace_table.cpp), embedded as read-only data. YL_TABLE_BIN is the file's
// path (CMakeLists.txt); young_laplace_table.cpp checks the size against the axes.
	.section .rodata
	.balign 16
	.globl capillary_yltable_values
	.hidden capillary_yltable_values
capillary_yltable_values:
	.incbin YL_TABLE_BIN
	.globl capillary_yltable_values_end
	.hidden capillary_yltable_values_end
capillary_yltable_values_end:
	.section .note.GNU-stack,"",@progbits
