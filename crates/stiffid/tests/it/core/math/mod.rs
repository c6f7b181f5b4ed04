mod spearman;
